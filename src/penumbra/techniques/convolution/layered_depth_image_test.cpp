#include "penumbra/techniques/convolution/layered_depth_image.h"

#include "penumbra/base/error.h"
#include "penumbra/base/memory_budget.h"
#include "penumbra/base/rng.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <utility>

namespace penumbra {
namespace {

// A sphere-like closed mesh: a base polyhedron (counter-clockwise from
// outside) whose triangles are split in four `levels` times, every vertex
// pushed onto the sphere. Midpoints are shared through a map, so the mesh
// stays closed.
TriangleMesh subdivided_sphere(std::vector<vec3> positions, std::vector<glm::uvec3> triangles, int levels,
                               float radius, vec3 centre) {
  for (vec3& p : positions) p = glm::normalize(p);
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<unsigned, unsigned>, unsigned> midpoint;
    auto middle = [&](unsigned a, unsigned b) {
      const auto key = std::minmax(a, b);
      const auto found = midpoint.find(key);
      if (found != midpoint.end()) return found->second;
      positions.push_back(glm::normalize(positions[a] + positions[b]));
      return midpoint[key] = unsigned(positions.size() - 1);
    };
    std::vector<glm::uvec3> finer;
    for (const glm::uvec3& t : triangles) {
      const unsigned ab = middle(t.x, t.y), bc = middle(t.y, t.z), ca = middle(t.z, t.x);
      finer.insert(finer.end(), {{t.x, ab, ca}, {ab, t.y, bc}, {ca, bc, t.z}, {ab, bc, ca}});
    }
    triangles = std::move(finer);
  }
  TriangleMesh mesh;
  for (const vec3& p : positions) mesh.positions.push_back(centre + radius * p);
  mesh.triangles = std::move(triangles);
  return mesh;
}

TriangleMesh icosphere(int levels, float radius = 1.0f, vec3 centre = vec3(0.0f)) {
  const float g = 1.6180339887f;  // golden ratio
  return subdivided_sphere({{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                            {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}},
                           {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                            {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                            {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}},
                           levels, radius, centre);
}

// From an octahedron: vertices on the axes and edges along the coordinate
// planes, so axis-aligned views put vertices and edges on pixel centres.
TriangleMesh octasphere(int levels, float radius = 1.0f, vec3 centre = vec3(0.0f)) {
  return subdivided_sphere({{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}},
                           {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}},
                           levels, radius, centre);
}

TriangleMesh box(vec3 lo, vec3 hi) {
  TriangleMesh mesh;
  for (int i = 0; i < 8; ++i) {
    mesh.positions.push_back(vec3(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z));
  }
  // Two triangles per face, counter-clockwise from outside.
  const unsigned faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (const auto& f : faces) {
    mesh.triangles.push_back({f[0], f[1], f[2]});
    mesh.triangles.push_back({f[0], f[2], f[3]});
  }
  return mesh;
}

CameraView look(vec3 eye, vec3 target, bool orthographic, float size, vec3 up = vec3(0, 0, 1)) {
  Camera c;
  c.eye = eye;
  c.target = target;
  c.up = up;
  c.projection = orthographic ? Projection::Orthographic : Projection::Perspective;
  if (orthographic) c.ortho_height = size;
  else c.fov_deg = size;
  return c.view();
}

// All crossings of a pixel's ray, by brute force over every triangle
// (Moller-Trumbore in double). `ambiguous` marks a ray that passes within
// kEdgeMargin (barycentric) of an edge, where which triangle it hits is the
// rasteriser's tie rule, not geometry.
struct Crossing {
  double depth;
  int object;
  bool entering;
  vec3 normal;
};

constexpr double kEdgeMargin = 1e-5;

std::vector<Crossing> brute_force(const std::vector<const TriangleMesh*>& meshes, const CameraView& cam, int x,
                                  int y, int width, int height, bool& ambiguous) {
  const Ray ray = cam.pixel_ray(float(x) + 0.5f, float(y) + 0.5f, width, height);
  const dvec3 o(ray.origin), d(ray.direction);
  std::vector<Crossing> hits;
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    for (const glm::uvec3& t : meshes[m]->triangles) {
      const dvec3 a(meshes[m]->positions[t.x]), b(meshes[m]->positions[t.y]), c(meshes[m]->positions[t.z]);
      const dvec3 e1 = b - a, e2 = c - a, p = glm::cross(d, e2);
      const double det = glm::dot(e1, p);
      if (det == 0.0) continue;
      const dvec3 s = o - a, q = glm::cross(s, e1);
      const double u = glm::dot(s, p) / det, v = glm::dot(d, q) / det, w = 1.0 - u - v;
      const double tt = glm::dot(e2, q) / det;
      const double margin = std::min({u, v, w});
      if (std::abs(margin) <= kEdgeMargin && tt > 0.0) ambiguous = true;
      if (margin <= 0.0 || tt <= 0.0) continue;
      const dvec3 n = glm::normalize(glm::cross(e1, e2));
      hits.push_back({glm::dot(o + tt * d - dvec3(cam.eye), dvec3(cam.forward)), int(m), glm::dot(n, d) < 0.0,
                      vec3(n)});
    }
  }
  std::sort(hits.begin(), hits.end(), [](const Crossing& a, const Crossing& b) { return a.depth < b.depth; });
  return hits;
}

// Every mesh's crossings on every pixel alternate, starting with entering
// (leaving for the meshes in `starts_inside`), and end outside.
void expect_parity(const LayeredDepthImage& ldi, int objects, std::vector<bool> starts_inside = {}) {
  starts_inside.resize(std::size_t(objects), false);
  const LdiView v = ldi.view();
  int failures = 0;
  for (int y = 0; y < v.height; ++y) {
    for (int x = 0; x < v.width; ++x) {
      const LdiPixel p = v.pixel(x, y);
      std::vector<bool> inside = starts_inside;
      bool ok = true;
      for (std::uint32_t i = 0; i < p.count; ++i) {
        const LdiFragment& f = p.fragments[i];
        ok = ok && f.object < objects && f.entering != inside[f.object];
        if (i > 0) ok = ok && p.fragments[i - 1].depth <= f.depth;
        if (f.object < objects) inside[f.object] = !inside[f.object];
      }
      for (int o = 0; o < objects; ++o) ok = ok && !inside[std::size_t(o)];
      if (!ok && ++failures <= 5) ADD_FAILURE() << "pixel (" << x << ", " << y << "): " << p.count << " crossings";
    }
  }
  EXPECT_EQ(failures, 0);
}

// The LDI equals brute force on every pixel whose ray passes clear of edges.
// Depths agree to 1e-4 relative: the LDI intersects the exact pixel-centre
// ray with the triangle's plane in double, brute force uses pixel_ray's float
// direction (rounding ~1e-7) and the depth is stored as a float.
void expect_brute_force(const LayeredDepthImage& ldi, const std::vector<const TriangleMesh*>& meshes,
                        const CameraView& cam, int* compared = nullptr) {
  const LdiView v = ldi.view();
  int failures = 0, clear = 0;
  for (int y = 0; y < v.height; ++y) {
    for (int x = 0; x < v.width; ++x) {
      bool ambiguous = false;
      const std::vector<Crossing> hits = brute_force(meshes, cam, x, y, v.width, v.height, ambiguous);
      if (ambiguous) continue;
      ++clear;
      const LdiPixel p = v.pixel(x, y);
      bool ok = p.count == hits.size();
      for (std::uint32_t i = 0; ok && i < p.count; ++i) {
        const LdiFragment& f = p.fragments[i];
        ok = std::abs(double(f.depth) - hits[i].depth) <= 1e-4 * (1.0 + std::abs(hits[i].depth)) &&
             int(f.object) == hits[i].object && f.entering == hits[i].entering &&
             glm::length(f.normal - hits[i].normal) < 1e-5f;
      }
      if (!ok && ++failures <= 5) {
        ADD_FAILURE() << "pixel (" << x << ", " << y << "): LDI " << p.count << " crossings, brute force "
                      << hits.size() << (p.count ? ", first LDI depth " + std::to_string(p.fragments[0].depth) : "")
                      << (hits.empty() ? "" : ", first brute depth " + std::to_string(hits[0].depth));
      }
    }
  }
  EXPECT_EQ(failures, 0);
  if (compared) *compared = clear;
}

std::vector<CameraView> random_cameras(std::uint64_t seed, int count, float distance) {
  Pcg32 rng(seed);
  std::vector<CameraView> cams;
  for (int i = 0; i < count; ++i) {
    const float z = 2.0f * rng.next_float() - 1.0f, phi = 2.0f * kPi * rng.next_float();
    const float r = std::sqrt(1.0f - z * z);
    const vec3 dir(r * std::cos(phi), r * std::sin(phi), z);
    const vec3 target(0.2f * rng.next_float() - 0.1f, 0.2f * rng.next_float() - 0.1f, 0.2f * rng.next_float() - 0.1f);
    const bool ortho = i % 2 == 0;
    cams.push_back(look(target + distance * dir, target, ortho, ortho ? 3.0f : 40.0f, vec3(0.3f, 0.2f, 1.0f)));
  }
  return cams;
}

TEST(LayeredDepthImage, ClosedMeshesGiveAlternatingCrossingsEqualToBruteForce) {
  const TriangleMesh sphere = icosphere(2, 1.0f, vec3(0.05f, -0.02f, 0.03f));
  const TriangleMesh cube = box(vec3(-0.8f, -0.6f, -0.7f), vec3(0.7f, 0.9f, 0.6f));
  for (const TriangleMesh* mesh : {&sphere, &cube}) {
    const std::vector<const TriangleMesh*> meshes{mesh};
    for (const CameraView& cam : random_cameras(7, 6, 4.0f)) {
      LayeredDepthImage ldi;
      ldi.build(meshes, cam, 48, 40);
      expect_parity(ldi, 1);
      int compared = 0;
      expect_brute_force(ldi, meshes, cam, &compared);
      EXPECT_GT(compared, 48 * 40 / 2);  // edges pass near few pixel centres
      EXPECT_GT(ldi.fragment_count(), 0u);
    }
  }
}

// Orthographic, looking down -z at a box whose edges, face diagonals and
// corners fall exactly on pixel centres (16 pixels over 8 world units, box
// +-1.25). Side faces are edge-on. The tie rule moves a centre on an edge by
// (+eps, +eps^2) in pixels (right, down): centres on the left (x = 5) and top
// (y = 5) edges count as inside, on the right (x = 10) and bottom (y = 10) as
// outside, so exactly the 5 x 5 pixels x, y in [5, 9] have two crossings.
TEST(LayeredDepthImage, SharedEdgesOnPixelCentresAreCountedOnce) {
  const TriangleMesh cube = box(vec3(-1.25f), vec3(1.25f));
  const std::vector<const TriangleMesh*> meshes{&cube};
  const CameraView cam = look(vec3(0, 0, 5), vec3(0), true, 8.0f, vec3(0, 1, 0));
  LayeredDepthImage ldi;
  ldi.build(meshes, cam, 16, 16);
  expect_parity(ldi, 1);
  for (int y = 0; y < 16; ++y) {
    for (int x = 0; x < 16; ++x) {
      const bool inside = x >= 5 && x <= 9 && y >= 5 && y <= 9;
      const LdiPixel p = ldi.view().pixel(x, y);
      ASSERT_EQ(p.count, inside ? 2u : 0u) << x << ", " << y;
      if (inside) {
        EXPECT_FLOAT_EQ(p.fragments[0].depth, 3.75f);  // front face z = 1.25, eye at 5
        EXPECT_FLOAT_EQ(p.fragments[1].depth, 6.25f);
        EXPECT_EQ(p.fragments[0].normal, vec3(0, 0, 1));
        EXPECT_EQ(p.fragments[1].normal, vec3(0, 0, -1));
      }
    }
  }
}

// Views along the axes of an octahedron-based sphere: its axis vertex projects
// onto the centre pixel's centre (odd image size), where eight triangles meet
// (four in front, four behind), and its meridian edges run along the centre
// row and column. Every pixel still has 0 or 2 crossings, and the centre
// pixel exactly 2.
TEST(LayeredDepthImage, VerticesOnPixelCentresAreCountedOnce) {
  const TriangleMesh sphere = octasphere(2);
  const std::vector<const TriangleMesh*> meshes{&sphere};
  for (bool ortho : {true, false}) {
    const CameraView cam = look(vec3(0, 0, 4), vec3(0), ortho, ortho ? 2.6f : 40.0f, vec3(0, 1, 0));
    LayeredDepthImage ldi;
    ldi.build(meshes, cam, 17, 17);
    expect_parity(ldi, 1);
    EXPECT_EQ(ldi.view().pixel(8, 8).count, 2u);
    EXPECT_NEAR(ldi.view().pixel(8, 8).fragments[0].depth, 3.0f, 1e-5f);
    expect_brute_force(ldi, meshes, cam);
  }
  // Silhouette vertices on pixel centres. A 16 x 17 image of height 4.25
  // (half width exactly 2 world units) puts x = -1.875 and +1.875 (a sphere of
  // that radius) on the centres of pixels (0, 8) and (15, 8), with every
  // projection step exact. There the front and back triangles fold and meet at
  // one depth; the tie rule moves the centre right, so the left vertex is
  // inside (two crossings at the same depth, entering then leaving) and the
  // right one outside.
  // Seen from both sides, both ways up (all exact), so each fold meets the
  // rasteriser's triangle order both ways round.
  const TriangleMesh big = octasphere(2, 1.875f);
  for (const vec3& eye : {vec3(0, 0, 4), vec3(0, 0, -4), vec3(0, 4, 0), vec3(0, -4, 0)}) {
    for (const float up : {1.0f, -1.0f}) {
      const CameraView cam = look(eye, vec3(0), true, 4.25f, eye.z != 0.0f ? vec3(0, up, 0) : vec3(0, 0, up));
      LayeredDepthImage ldi;
      ldi.build({&big}, cam, 16, 17);
      expect_parity(ldi, 1);
      ASSERT_EQ(ldi.view().pixel(0, 8).count, 2u);
      EXPECT_EQ(ldi.view().pixel(15, 8).count, 0u);
      EXPECT_NEAR(ldi.view().pixel(0, 8).fragments[0].depth, 4.0f, 1e-5f);
      EXPECT_NEAR(ldi.view().pixel(0, 8).fragments[1].depth, 4.0f, 1e-5f);
    }
  }
}

TEST(LayeredDepthImage, NormalsAreUnitAndOutward) {
  const vec3 centre(0.1f, 0.2f, -0.1f);
  const TriangleMesh sphere = icosphere(2, 1.0f, centre);
  const TriangleMesh cube = box(vec3(-1.0f), vec3(1.0f));
  for (const TriangleMesh* mesh : {&sphere, &cube}) {
    const vec3 mesh_centre = mesh == &sphere ? centre : vec3(0.0f);
    for (const CameraView& cam : random_cameras(11, 4, 5.0f)) {
      LayeredDepthImage ldi;
      ldi.build({mesh}, cam, 32, 32);
      const LdiView v = ldi.view();
      for (int y = 0; y < 32; ++y) {
        for (int x = 0; x < 32; ++x) {
          const Ray ray = cam.pixel_ray(float(x) + 0.5f, float(y) + 0.5f, 32, 32);
          const LdiPixel p = v.pixel(x, y);
          for (std::uint32_t i = 0; i < p.count; ++i) {
            const LdiFragment& f = p.fragments[i];
            ASSERT_NEAR(glm::length(f.normal), 1.0f, 1e-6f);
            const vec3 hit = ray.at(f.depth / glm::dot(ray.direction, cam.forward));
            // Outward: away from the centre of these convex meshes.
            EXPECT_GT(glm::dot(f.normal, hit - mesh_centre), 0.0f);
            // Entering agrees with the normal wherever the ray is not grazing.
            if (std::abs(glm::dot(f.normal, ray.direction)) > 1e-3f) {
              EXPECT_EQ(f.entering, glm::dot(f.normal, ray.direction) < 0.0f);
            }
          }
        }
      }
    }
  }
}

// A camera inside the mesh: the clipped triangles still close up in front of
// it, every pixel has an odd number of crossings and the first one leaves.
TEST(LayeredDepthImage, CameraInsideStartsInside) {
  const TriangleMesh sphere = icosphere(2);
  const TriangleMesh cube = box(vec3(-1.0f, -0.5f, -0.7f), vec3(0.8f, 1.2f, 0.9f));
  const vec3 eyes[] = {vec3(0.1f, -0.2f, 0.15f), vec3(-0.5f, 0.4f, 0.3f), vec3(0.7f, 0.0f, 0.0f)};
  const vec3 targets[] = {vec3(1.0f, 0.3f, -0.2f), vec3(0.0f, -2.0f, 0.1f), vec3(-1.0f, 0.5f, 0.6f)};
  for (const TriangleMesh* mesh : {&sphere, &cube}) {
    for (int i = 0; i < 3; ++i) {
      const CameraView cam = look(eyes[i], targets[i], false, 100.0f);
      LayeredDepthImage ldi;
      ldi.build({mesh}, cam, 40, 32);
      expect_parity(ldi, 1, {true});
      const LdiView v = ldi.view();
      for (int y = 0; y < 32; ++y) {
        for (int x = 0; x < 40; ++x) {
          ASSERT_EQ(v.pixel(x, y).count % 2, 1u) << x << ", " << y;
          EXPECT_FALSE(v.pixel(x, y).fragments[0].entering);
        }
      }
      expect_brute_force(ldi, {mesh}, cam);
    }
  }
}

// A long box reaching behind an outside camera: the parts behind the eye are
// clipped away and the rays in front still get even, alternating counts.
TEST(LayeredDepthImage, MeshBehindTheCameraIsClipped) {
  const TriangleMesh beam = box(vec3(-0.5f, -0.5f, -10.0f), vec3(0.5f, 0.5f, 10.0f));
  const std::vector<const TriangleMesh*> meshes{&beam};
  const CameraView cam = look(vec3(0.2f, 1.5f, 0.1f), vec3(0.4f, 0.0f, 1.5f), false, 120.0f, vec3(1, 0, 0));
  LayeredDepthImage ldi;
  ldi.build(meshes, cam, 48, 48);
  expect_parity(ldi, 1);
  expect_brute_force(ldi, meshes, cam);
  EXPECT_GT(ldi.fragment_count(), 48u * 48u / 4u);
}

TEST(LayeredDepthImage, TwoMeshesKeepTheirObjectIds) {
  const TriangleMesh sphere = icosphere(2, 1.0f);
  const TriangleMesh cube = box(vec3(0.3f, 0.2f, -0.4f), vec3(1.6f, 1.4f, 0.8f));  // overlaps the sphere
  const std::vector<const TriangleMesh*> meshes{&sphere, &cube};
  int seen[2] = {0, 0};
  for (const CameraView& cam : random_cameras(23, 4, 5.0f)) {
    LayeredDepthImage ldi;
    ldi.build(meshes, cam, 40, 40);
    expect_parity(ldi, 2);
    expect_brute_force(ldi, meshes, cam);  // compares the object of every crossing
    for (std::size_t i = 0; i < ldi.fragment_count(); ++i) ++seen[ldi.view().fragments[i].object];
  }
  EXPECT_GT(seen[0], 0);
  EXPECT_GT(seen[1], 0);
}

TEST(LayeredDepthImage, BudgetAndBadInput) {
  const TriangleMesh sphere = icosphere(1);
  const CameraView cam = look(vec3(0, -4, 0), vec3(0), false, 40.0f);
  LayeredDepthImage ldi;
  // 10^12 pixels need terabytes of offsets: refused before any allocation.
  EXPECT_THROW(ldi.build({&sphere}, cam, 1000000, 1000000), OutOfMemoryBudget);
  // A budget that holds the offsets but not the fragments.
  const std::uint64_t saved = memory_budget_bytes();
  set_memory_budget_bytes(64 * 64 * 8 + 64 * 64 * 8);
  EXPECT_THROW(ldi.build({&sphere}, cam, 64, 64), OutOfMemoryBudget);
  set_memory_budget_bytes(saved);
  EXPECT_EQ(ldi.fragment_count(), 0u);
  EXPECT_EQ(ldi.width(), 0);

  EXPECT_THROW(ldi.build({&sphere}, cam, 0, 10), InvalidArgument);
  EXPECT_THROW(ldi.build({nullptr}, cam, 8, 8), InvalidArgument);
  TriangleMesh broken = sphere;
  broken.triangles[3].y = unsigned(broken.positions.size());
  EXPECT_THROW(ldi.build({&broken}, cam, 8, 8), InvalidArgument);

  ldi.build({&sphere}, cam, 64, 64);
  EXPECT_EQ(ldi.bytes(), (64u * 64u + 1u) * 4u + ldi.fragment_count() * sizeof(LdiFragment));
  ldi.build({}, cam, 8, 8);  // no meshes: an empty image
  EXPECT_EQ(ldi.fragment_count(), 0u);
  EXPECT_EQ(ldi.view().pixel(7, 7).count, 0u);
}

// Not a timing assertion: prints the build time of an ~80k-triangle sphere.
TEST(LayeredDepthImage, TimingPrint) {
  const TriangleMesh sphere = icosphere(6, 1.0f);
  const CameraView cam = look(vec3(0.5f, -3.0f, 1.0f), vec3(0), false, 45.0f);
  LayeredDepthImage ldi;
  ldi.build({&sphere}, cam, 512, 512);  // warm-up (first allocation)
  const auto start = std::chrono::steady_clock::now();
  ldi.build({&sphere}, cam, 512, 512);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  std::printf("[ timing ] LDI of %zu triangles at 512x512: %.1f ms, %zu fragments, %.1f MB\n",
              sphere.triangles.size(), ms, ldi.fragment_count(), double(ldi.bytes()) / 1e6);
  expect_parity(ldi, 1);
}

}  // namespace
}  // namespace penumbra

namespace penumbra {
namespace {

// The same mesh with every triangle on its own three vertices, as a file
// split at seams everywhere would give.
TriangleMesh unwelded(const TriangleMesh& mesh) {
  TriangleMesh out;
  for (const glm::uvec3& t : mesh.triangles) {
    const unsigned base = unsigned(out.positions.size());
    for (int k = 0; k < 3; ++k) out.positions.push_back(mesh.positions[t[k]]);
    out.triangles.push_back({base, base + 1, base + 2});
  }
  return out;
}

double angle_deg(vec3 a, vec3 b) {
  const double c = std::clamp(glm::dot(dvec3(glm::normalize(a)), dvec3(glm::normalize(b))), -1.0, 1.0);
  return std::acos(c) * 180.0 / double(kPi);
}

// On a level-2 icosphere (edges ~16 degrees of arc) a flat normal is off the
// sphere's normal by up to about half an edge, ~9 degrees, at the corners.
// The interpolated one is exact wherever the corner normals are radial: the
// hit point is sum b_i v_i = centre + r sum b_i n_i, so its direction from
// the centre is the renormalised sum b_i n_i. Only the area-weighted fans'
// asymmetry (valence 5 and 6 vertices, unequal triangles) leaves an error,
// measured 1.3 degrees against 10.7 flat; 1/4 of the flat
// error leaves room for that and fails for any scheme that stays faceted
// (or interpolates with wrong barycentrics: wrong weights on 16-degree
// apart normals move them by degrees).
TEST(LayeredDepthImage, SmoothNormalsFollowTheSphere) {
  const vec3 centre(0.1f, -0.2f, 0.15f);
  const float radius = 1.5f;
  const TriangleMesh sphere = icosphere(2, radius, centre);
  const std::vector<vec3> corners = smooth_corner_normals(sphere);
  ASSERT_EQ(corners.size(), 3 * sphere.triangles.size());
  double flat_max = 0.0, smooth_max = 0.0;
  int fragments = 0;
  for (const CameraView& cam : random_cameras(5, 4, 6.0f)) {
    LayeredDepthImage flat, smooth;
    flat.build({&sphere}, cam, 48, 48);
    smooth.build({&sphere}, {&corners}, cam, 48, 48);
    ASSERT_EQ(flat.fragment_count(), smooth.fragment_count());
    for (int y = 0; y < 48; ++y) {
      for (int x = 0; x < 48; ++x) {
        const Ray ray = cam.pixel_ray(float(x) + 0.5f, float(y) + 0.5f, 48, 48);
        const LdiPixel pf = flat.view().pixel(x, y), ps = smooth.view().pixel(x, y);
        ASSERT_EQ(pf.count, ps.count);
        for (std::uint32_t i = 0; i < ps.count; ++i) {
          const LdiFragment &f = pf.fragments[i], &s = ps.fragments[i];
          // Only the normal changes.
          EXPECT_EQ(f.depth, s.depth);
          EXPECT_EQ(f.entering, s.entering);
          EXPECT_EQ(f.object, s.object);
          ASSERT_NEAR(glm::length(s.normal), 1.0f, 1e-6f);
          EXPECT_GT(glm::dot(s.normal, f.normal), 0.0f);
          const vec3 hit = ray.at(s.depth / glm::dot(ray.direction, cam.forward));
          const vec3 analytic = hit - centre;
          flat_max = std::max(flat_max, angle_deg(f.normal, analytic));
          smooth_max = std::max(smooth_max, angle_deg(s.normal, analytic));
          ++fragments;
        }
      }
    }
  }
  ASSERT_GT(fragments, 1000);
  std::printf("sphere normals, max error: flat %.3f deg, smooth %.3f deg (%d fragments)\n", flat_max, smooth_max,
              fragments);
  EXPECT_GT(flat_max, 5.0);
  EXPECT_LT(smooth_max, 0.25 * flat_max);
}

// Vertices split at seams are welded by position: the soup of separate
// triangles gets the same corner normals as the shared-vertex mesh.
TEST(LayeredDepthImage, SmoothNormalsWeldEqualPositions) {
  const TriangleMesh sphere = icosphere(1, 2.0f, vec3(0.5f, 0.0f, -1.0f));
  const std::vector<vec3> shared = smooth_corner_normals(sphere);
  const std::vector<vec3> split = smooth_corner_normals(unwelded(sphere));
  ASSERT_EQ(shared.size(), split.size());
  double most = 0.0, off_flat = 0.0;
  for (std::size_t c = 0; c < shared.size(); ++c) {
    ASSERT_NEAR(glm::length(split[c]), 1.0f, 1e-6f);
    most = std::max(most, double(glm::length(shared[c] - split[c])));
    const glm::uvec3 t = sphere.triangles[c / 3];
    const vec3 face = glm::normalize(glm::cross(sphere.positions[t.y] - sphere.positions[t.x],
                                                sphere.positions[t.z] - sphere.positions[t.x]));
    off_flat = std::max(off_flat, angle_deg(split[c], face));
  }
  EXPECT_LT(most, 1e-6);
  EXPECT_GT(off_flat, 5.0);  // really smoothed, not the face normals
}

// A box's edges are 90 degrees, beyond the default 60-degree crease: its
// faces keep their exact normals. Without a crease (180 degrees) its corners
// are averaged and the faces get interpolated normals, still unit, outward
// and on the faces' outer side.
TEST(LayeredDepthImage, SmoothNormalsKeepCreases) {
  const TriangleMesh cube = box(vec3(-1.0f, -0.8f, -0.6f), vec3(0.9f, 1.1f, 0.7f));
  const std::vector<vec3> creased = smooth_corner_normals(cube);
  const std::vector<vec3> rounded = smooth_corner_normals(cube, 180.0f);
  for (const CameraView& cam : random_cameras(17, 4, 6.0f)) {
    LayeredDepthImage flat, sharp, round;
    flat.build({&cube}, cam, 32, 32);
    sharp.build({&cube}, {&creased}, cam, 32, 32);
    round.build({&cube}, {&rounded}, cam, 32, 32);
    ASSERT_EQ(flat.fragment_count(), sharp.fragment_count());
    ASSERT_EQ(flat.fragment_count(), round.fragment_count());
    double rounded_off = 0.0;
    for (std::size_t i = 0; i < flat.fragment_count(); ++i) {
      const LdiFragment &f = flat.view().fragments[i], &s = sharp.view().fragments[i], &r = round.view().fragments[i];
      // Axis-aligned faces: the flat normal is an exact axis.
      EXPECT_NEAR(std::max({std::abs(f.normal.x), std::abs(f.normal.y), std::abs(f.normal.z)}), 1.0f, 1e-6f);
      EXPECT_LT(glm::length(s.normal - f.normal), 1e-6f);
      ASSERT_NEAR(glm::length(r.normal), 1.0f, 1e-6f);
      EXPECT_GT(glm::dot(r.normal, f.normal), 0.0f);
      EXPECT_EQ(r.entering, f.entering);
      rounded_off = std::max(rounded_off, angle_deg(r.normal, f.normal));
    }
    EXPECT_GT(rounded_off, 10.0);
  }
}

TEST(LayeredDepthImage, CornerNormalsOfTheWrongSizeAreRejected) {
  const TriangleMesh sphere = icosphere(0);
  const CameraView cam = look(vec3(0, -5, 0), vec3(0.0f), true, 3.0f);
  const std::vector<vec3> short_list(3 * sphere.triangles.size() - 1, vec3(0, 0, 1));
  LayeredDepthImage ldi;
  EXPECT_THROW(ldi.build({&sphere}, {&short_list}, cam, 8, 8), InvalidArgument);
  EXPECT_THROW(ldi.build({&sphere, &sphere}, {nullptr}, cam, 8, 8), InvalidArgument);
  EXPECT_NO_THROW(ldi.build({&sphere, &sphere}, {nullptr, nullptr}, cam, 8, 8));
}

}  // namespace
}  // namespace penumbra

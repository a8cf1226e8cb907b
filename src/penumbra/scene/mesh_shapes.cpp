// Built-in closed meshes (see mesh_shapes.h). Each generator places vertices
// on the exact surface and connects them so every edge is shared by two
// triangles with opposite directions; the winding rules are noted where the
// triangles are made.
#include "penumbra/scene/mesh_shapes.h"

#include "penumbra/base/error.h"
#include "penumbra/base/memory_budget.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <unordered_map>

namespace penumbra {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

struct ShapeInfo {
  std::string_view name;
  int default_resolution;
  int max_resolution;  // keeps the triangle count near or below 4 million
  int min_resolution;
};

constexpr std::array<ShapeInfo, 5> kShapes = {{
    {"sphere", 3, 8, 1},          // 20 * 4^8 = 1.3M triangles
    {"box", 1, 512, 1},           // 12 * 512^2 = 3.1M
    {"torus", 32, 1000, 3},       // 4 * 1000^2 = 4.0M
    {"torus-knot", 16, 352, 3},   // 32 * 352^2 = 4.0M
    {"disk", 64, 1000000, 3},     // 4 * 10^6
}};

void reserve_checked(TriangleMesh& mesh, std::string_view name, std::uint64_t vertices, std::uint64_t triangles) {
  check_memory_budget(fmt::format("built-in mesh '{}'", name),
                      checked_product({vertices, sizeof(vec3)}) + checked_product({triangles, sizeof(glm::uvec3)}));
  mesh.positions.reserve(static_cast<std::size_t>(vertices));
  mesh.triangles.reserve(static_cast<std::size_t>(triangles));
}

// Two triangles per quad of a grid that wraps around in both directions;
// vertex (row, col) is row * cols + col. The triangles face along
// d(position)/d(row) x d(position)/d(col).
void add_periodic_grid(TriangleMesh& mesh, std::uint32_t rows, std::uint32_t cols) {
  for (std::uint32_t r = 0; r < rows; ++r) {
    const std::uint32_t r1 = (r + 1) % rows;
    for (std::uint32_t c = 0; c < cols; ++c) {
      const std::uint32_t c1 = (c + 1) % cols;
      const std::uint32_t a = r * cols + c, b = r1 * cols + c, d = r1 * cols + c1, e = r * cols + c1;
      mesh.triangles.emplace_back(a, b, d);
      mesh.triangles.emplace_back(a, d, e);
    }
  }
}

// The icosahedron's 12 vertices are the cyclic permutations of (0, +-1,
// +-phi); its faces are the triples of mutually adjacent vertices (distance 2
// apart). Each level splits every triangle into four at the edge midpoints,
// pushed out to the unit sphere.
TriangleMesh make_sphere(int level) {
  const float phi = (1.0f + std::sqrt(5.0f)) / 2.0f;
  std::vector<vec3> corners;
  for (float a : {-1.0f, 1.0f}) {
    for (float b : {-phi, phi}) {
      corners.emplace_back(0.0f, a, b);
      corners.emplace_back(a, b, 0.0f);
      corners.emplace_back(b, 0.0f, a);
    }
  }
  const auto adjacent = [&](std::size_t i, std::size_t j) {
    return std::abs(glm::distance(corners[i], corners[j]) - 2.0f) < 1e-3f;
  };
  std::uint64_t triangle_count = 20;
  for (int l = 0; l < level; ++l) triangle_count *= 4;
  TriangleMesh mesh;
  // A closed triangle mesh of genus 0 has V = T / 2 + 2 vertices.
  reserve_checked(mesh, "sphere", triangle_count / 2 + 2, triangle_count);
  for (const vec3& c : corners) mesh.positions.push_back(glm::normalize(c));
  for (std::uint32_t i = 0; i < 12; ++i) {
    for (std::uint32_t j = i + 1; j < 12; ++j) {
      for (std::uint32_t k = j + 1; k < 12; ++k) {
        if (!adjacent(i, j) || !adjacent(j, k) || !adjacent(i, k)) continue;
        const vec3 normal = glm::cross(corners[j] - corners[i], corners[k] - corners[i]);
        // The solid is convex around the origin: outward means away from it.
        if (glm::dot(normal, corners[i]) > 0.0f) {
          mesh.triangles.emplace_back(i, j, k);
        } else {
          mesh.triangles.emplace_back(i, k, j);
        }
      }
    }
  }
  for (int l = 0; l < level; ++l) {
    std::unordered_map<std::uint64_t, std::uint32_t> midpoints;
    midpoints.reserve(mesh.triangles.size() * 3 / 2);
    const auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      const std::uint64_t key = (std::uint64_t(std::min(a, b)) << 32) | std::max(a, b);
      const auto [it, inserted] = midpoints.try_emplace(key, static_cast<std::uint32_t>(mesh.positions.size()));
      if (inserted) mesh.positions.push_back(glm::normalize(mesh.positions[a] + mesh.positions[b]));
      return it->second;
    };
    std::vector<glm::uvec3> finer;
    finer.reserve(mesh.triangles.size() * 4);
    for (const glm::uvec3& t : mesh.triangles) {
      const std::uint32_t ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]), ca = midpoint(t[2], t[0]);
      // The four children keep the parent's winding.
      finer.emplace_back(t[0], ab, ca);
      finer.emplace_back(ab, t[1], bc);
      finer.emplace_back(ca, bc, t[2]);
      finer.emplace_back(ab, bc, ca);
    }
    mesh.triangles = std::move(finer);
  }
  return mesh;
}

// Each face is an n x n grid on the lattice {0..n}^3 of the cube's surface;
// lattice points are shared between faces so the seams are closed.
TriangleMesh make_box(int n) {
  const auto un = static_cast<std::uint64_t>(n);
  TriangleMesh mesh;
  reserve_checked(mesh, "box", 6 * un * un + 2, 12 * un * un);
  std::unordered_map<std::uint64_t, std::uint32_t> lattice;
  const auto vertex = [&](glm::uvec3 l) {
    const std::uint64_t key = (std::uint64_t(l.x) * (un + 1) + l.y) * (un + 1) + l.z;
    const auto [it, inserted] = lattice.try_emplace(key, static_cast<std::uint32_t>(mesh.positions.size()));
    if (inserted) mesh.positions.push_back(vec3(l) * (2.0f / static_cast<float>(n)) - 1.0f);
    return it->second;
  };
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;  // e_u x e_v = e_axis
    for (bool positive : {false, true}) {
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
          const auto corner = [&](int di, int dj) {
            glm::uvec3 l;
            l[axis] = positive ? static_cast<unsigned>(n) : 0u;
            l[u] = static_cast<unsigned>(i + di);
            l[v] = static_cast<unsigned>(j + dj);
            return vertex(l);
          };
          const std::uint32_t a = corner(0, 0), b = corner(1, 0), c = corner(1, 1), d = corner(0, 1);
          if (positive) {  // a -> b -> c turns from e_u to e_v: facing +e_axis
            mesh.triangles.emplace_back(a, b, c);
            mesh.triangles.emplace_back(a, c, d);
          } else {
            mesh.triangles.emplace_back(a, c, b);
            mesh.triangles.emplace_back(a, d, c);
          }
        }
      }
    }
  }
  return mesh;
}

// Rows go around the z axis (angle theta), columns around the tube (phi):
// d/dtheta x d/dphi points away from the tube's centre line.
TriangleMesh make_torus(int n) {
  constexpr float kMajor = 0.7f, kMinor = 0.3f;
  const auto rows = static_cast<std::uint32_t>(2 * n), cols = static_cast<std::uint32_t>(n);
  TriangleMesh mesh;
  reserve_checked(mesh, "torus", std::uint64_t(rows) * cols, 2 * std::uint64_t(rows) * cols);
  for (std::uint32_t r = 0; r < rows; ++r) {
    const float theta = 2.0f * kPi * static_cast<float>(r) / static_cast<float>(rows);
    for (std::uint32_t c = 0; c < cols; ++c) {
      const float phi = 2.0f * kPi * static_cast<float>(c) / static_cast<float>(cols);
      const float radius = kMajor + kMinor * std::cos(phi);
      mesh.positions.emplace_back(radius * std::cos(theta), radius * std::sin(theta), kMinor * std::sin(phi));
    }
  }
  add_periodic_grid(mesh, rows, cols);
  return mesh;
}

// The (2,3) torus knot on the torus of radii 2 and 1, c(t) = ((2 + cos 3t)
// cos 2t, (2 + cos 3t) sin 2t, -sin 3t), scaled by 0.85 / 3 so the tube of
// radius 0.15 reaches at most 1 from the z axis. Strands stay at least 0.47
// apart and the radius of curvature at least 0.40, so the tube does not
// intersect itself. The tube's frame is the torus normal u (perpendicular to
// the curve, which lies on the torus) and T x u: smooth and periodic, with no
// inflection problems of the Frenet frame.
TriangleMesh make_torus_knot(int n) {
  constexpr double kTube = 0.15;
  constexpr double kScale = 0.85 / 3.0;
  // Rows go around the tube (phi), columns along the curve (t):
  // d/dphi x d/dt points away from the curve.
  const auto rows = static_cast<std::uint32_t>(n), cols = static_cast<std::uint32_t>(16 * n);
  TriangleMesh mesh;
  reserve_checked(mesh, "torus-knot", std::uint64_t(rows) * cols, 2 * std::uint64_t(rows) * cols);
  mesh.positions.resize(std::size_t(rows) * cols);
  for (std::uint32_t c = 0; c < cols; ++c) {
    const double t = 2.0 * std::numbers::pi * static_cast<double>(c) / static_cast<double>(cols);
    const double cos2 = std::cos(2.0 * t), sin2 = std::sin(2.0 * t);
    const double cos3 = std::cos(3.0 * t), sin3 = std::sin(3.0 * t);
    const double radius = 2.0 + cos3;
    const dvec3 centre(radius * cos2, radius * sin2, -sin3);
    const dvec3 tangent =
        glm::normalize(dvec3(-3.0 * sin3 * cos2 - 2.0 * radius * sin2, -3.0 * sin3 * sin2 + 2.0 * radius * cos2,
                             -3.0 * cos3));
    const dvec3 normal(cos3 * cos2, cos3 * sin2, -sin3);
    const dvec3 binormal = glm::cross(tangent, normal);  // (normal, binormal, tangent) is right-handed
    for (std::uint32_t r = 0; r < rows; ++r) {
      const double phi = 2.0 * std::numbers::pi * static_cast<double>(r) / static_cast<double>(rows);
      const dvec3 p = kScale * centre + kTube * (std::cos(phi) * normal + std::sin(phi) * binormal);
      mesh.positions[std::size_t(r) * cols + c] = vec3(p);
    }
  }
  add_periodic_grid(mesh, rows, cols);
  return mesh;
}

// Caps are fans around their centres, the side one quad per rim segment.
TriangleMesh make_disk(int n) {
  constexpr float kHalfThickness = 0.025f;
  const auto segments = static_cast<std::uint32_t>(n);
  TriangleMesh mesh;
  reserve_checked(mesh, "disk", 2 * std::uint64_t(segments) + 2, 4 * std::uint64_t(segments));
  const std::uint32_t top_centre = 0, bottom_centre = 1;
  mesh.positions.emplace_back(0.0f, 0.0f, kHalfThickness);
  mesh.positions.emplace_back(0.0f, 0.0f, -kHalfThickness);
  for (std::uint32_t k = 0; k < segments; ++k) {
    const float angle = 2.0f * kPi * static_cast<float>(k) / static_cast<float>(segments);
    mesh.positions.emplace_back(std::cos(angle), std::sin(angle), kHalfThickness);
    mesh.positions.emplace_back(std::cos(angle), std::sin(angle), -kHalfThickness);
  }
  const auto top = [](std::uint32_t k) { return 2 + 2 * k; };
  const auto bottom = [](std::uint32_t k) { return 3 + 2 * k; };
  for (std::uint32_t k = 0; k < segments; ++k) {
    const std::uint32_t k1 = (k + 1) % segments;
    mesh.triangles.emplace_back(top_centre, top(k), top(k1));           // counter-clockwise seen from +z
    mesh.triangles.emplace_back(bottom_centre, bottom(k1), bottom(k));  // counter-clockwise seen from -z
    // Rim: along the angle, then up, faces outward.
    mesh.triangles.emplace_back(bottom(k), bottom(k1), top(k1));
    mesh.triangles.emplace_back(bottom(k), top(k1), top(k));
  }
  return mesh;
}

}  // namespace

std::shared_ptr<TriangleMesh> make_builtin_mesh(std::string_view name, int resolution) {
  const ShapeInfo* shape = nullptr;
  for (const ShapeInfo& s : kShapes) {
    if (s.name == name) shape = &s;
  }
  if (!shape) {
    std::string known;
    for (const ShapeInfo& s : kShapes) known += (known.empty() ? "" : ", ") + std::string(s.name);
    throw InvalidArgument("builtin", fmt::format("unknown built-in mesh '{}' (known: {})", name, known));
  }
  if (resolution == 0) resolution = shape->default_resolution;
  if (resolution < shape->min_resolution || resolution > shape->max_resolution) {
    throw InvalidArgument("resolution", fmt::format("'{}' resolution must be in [{}, {}] (0 = default {}), got {}",
                                                    name, shape->min_resolution, shape->max_resolution,
                                                    shape->default_resolution, resolution));
  }
  TriangleMesh mesh;
  if (name == "sphere") {
    mesh = make_sphere(resolution);
  } else if (name == "box") {
    mesh = make_box(resolution);
  } else if (name == "torus") {
    mesh = make_torus(resolution);
  } else if (name == "torus-knot") {
    mesh = make_torus_knot(resolution);
  } else {
    mesh = make_disk(resolution);
  }
  return std::make_shared<TriangleMesh>(std::move(mesh));
}

const std::vector<std::pair<std::string, std::string>>& builtin_meshes() {
  static const std::vector<std::pair<std::string, std::string>> kList = {
      {"sphere", "radius 1, subdivided icosahedron; resolution = subdivision level (default 3, max 8)"},
      {"box", "cube of half-extent 1; resolution = quads along a face edge (default 1: 12 triangles)"},
      {"torus", "major radius 0.7, minor 0.3, axis z; resolution = segments around the tube (default 32)"},
      {"torus-knot", "tube of radius 0.15 around the (2,3) torus knot; resolution = segments around the tube "
                     "(default 16)"},
      {"disk", "closed cylinder of radius 1 and thickness 0.05, axis z (Patel et al. 2013, Fig. 14 occluder); "
               "resolution = rim segments (default 64)"},
  };
  return kList;
}

}  // namespace penumbra

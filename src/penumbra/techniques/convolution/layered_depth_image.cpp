#include "penumbra/techniques/convolution/layered_depth_image.h"

#include "penumbra/base/error.h"
#include "penumbra/base/memory_budget.h"
#include "penumbra/base/parallel.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <string>

// The coverage decision relies on every edge function being evaluated by the
// same IEEE operations from both triangles of an edge; this file is built with
// -ffp-contract=off (CMakeLists.txt) so no fused multiply-add changes one copy.

namespace penumbra {
namespace {

constexpr int kBandRows = 8;  // rows per parallel band
// Perspective near plane as a fraction of the farthest vertex distance: close
// enough to the eye that nothing visible is lost, far enough that 1 / depth
// stays finite in pixel space.
constexpr double kNearFraction = 1e-6;

struct CameraVertex {
  dvec3 cam;         // (right, up, forward) coordinates relative to the eye
  glm::dvec2 pixel;  // continuous pixel coordinates (valid when cam.z >= near)
};

// World -> camera -> pixel mapping, the exact inverse of CameraView::pixel_ray.
struct Projector {
  dvec3 eye, right, up, forward;
  double half_width = 1.0, half_height = 1.0;  // of the image plane at unit depth (orthographic: world)
  double width = 1.0, height = 1.0;
  bool orthographic = false;

  dvec3 to_camera(vec3 p) const {
    const dvec3 d = dvec3(p) - eye;
    return dvec3(glm::dot(d, right), glm::dot(d, up), glm::dot(d, forward));
  }
  glm::dvec2 to_pixel(dvec3 c) const {
    double sx = c.x, sy = c.y;
    if (!orthographic) {
      sx /= c.z;
      sy /= c.z;
    }
    return glm::dvec2((sx / half_width + 1.0) * 0.5 * width, (1.0 - sy / half_height) * 0.5 * height);
  }
  // Image-plane coordinates (U, V) of a pixel point: the ray is
  // eye + z (U r + V u + f) (perspective) or eye + U r + V u + z f.
  glm::dvec2 image_plane(double px, double py) const {
    return glm::dvec2((2.0 * px / width - 1.0) * half_width, (1.0 - 2.0 * py / height) * half_height);
  }
};

// An edge function with its endpoints in a fixed (lexicographic) order, so
// both triangles of a shared edge compute the same value; `flip` restores the
// triangle's own direction. `tie` is the sign at points exactly on the edge:
// that of the value at the point moved by (+eps, +eps^2).
struct Edge {
  double ax = 0.0, ay = 0.0, dx = 0.0, dy = 0.0;
  int tie = 0;  // 0: degenerate edge
  bool flip = false;
};

Edge make_edge(glm::dvec2 a, glm::dvec2 b) {
  Edge e;
  e.flip = b.x < a.x || (b.x == a.x && b.y < a.y);
  if (e.flip) std::swap(a, b);
  e.ax = a.x;
  e.ay = a.y;
  e.dx = b.x - a.x;
  e.dy = b.y - a.y;
  // value(p) = dx (p.y - ay) - dy (p.x - ax): d/dpx = -dy, d/dpy = dx.
  e.tie = e.dy < 0.0 ? 1 : (e.dy > 0.0 ? -1 : (e.dx > 0.0 ? 1 : (e.dx < 0.0 ? -1 : 0)));
  return e;
}

// row_term = e.dx * (py - e.ay), the same for the whole row.
inline int edge_side(const Edge& e, double row_term, double px) {
  const double v = row_term - e.dy * (px - e.ax);
  const int s = v > 0.0 ? 1 : (v < 0.0 ? -1 : e.tie);
  return e.flip ? -s : s;
}

// One triangle as seen from the camera: the up to two pixel-space triangles
// left after clipping against the near plane, and what its fragments need
// (computed only once a pixel is covered, see attributes()).
struct SetupTriangle {
  int pieces = 0;
  glm::dvec2 piece[2][3];
  const CameraVertex* vertex[3] = {nullptr, nullptr, nullptr};
  const vec3* position[3] = {nullptr, nullptr, nullptr};  // world
  const vec3* corner_normals = nullptr;                    // 3 shading normals, or null: flat
  std::uint16_t object = 0;
};

struct TriangleAttributes {
  dvec3 plane_normal;  // camera space; plane: dot(plane_normal, c) = plane_offset
  double plane_offset = 0.0;
  vec3 world_normal{0.0f};
};

TriangleAttributes attributes(const SetupTriangle& s) {
  TriangleAttributes a;
  const dvec3 &c0 = s.vertex[0]->cam, &c1 = s.vertex[1]->cam, &c2 = s.vertex[2]->cam;
  a.plane_normal = glm::cross(c1 - c0, c2 - c0);
  a.plane_offset = glm::dot(a.plane_normal, c0);
  const dvec3 p0(*s.position[0]), p1(*s.position[1]), p2(*s.position[2]);
  const dvec3 n = glm::cross(p1 - p0, p2 - p0);
  const double length = glm::length(n);
  // Zero only for a triangle without area, which covers a pixel centre only
  // through rounding; it then gets no normal rather than a NaN one.
  if (length > 0.0) a.world_normal = vec3(n / length);
  return a;
}

struct MeshTables {
  const std::vector<const TriangleMesh*>* meshes = nullptr;
  const std::vector<const std::vector<vec3>*>* corner_normals = nullptr;  // empty: all flat
  std::vector<std::size_t> triangle_begin;  // per mesh, + total
  std::vector<std::size_t> vertex_begin;
};

struct BuildContext {
  const MeshTables* tables = nullptr;
  const CameraVertex* vertices = nullptr;
  Projector projector;
  double near = 0.0;
  int width = 0, height = 0;
};

// The point where segment inside -> outside crosses z = near. Both triangles
// of the edge pass the endpoints in the same roles, so get the same point.
CameraVertex clip_point(const CameraVertex& inside, const CameraVertex& outside, const BuildContext& ctx) {
  const double t = (ctx.near - inside.cam.z) / (outside.cam.z - inside.cam.z);
  CameraVertex r;
  r.cam = inside.cam + t * (outside.cam - inside.cam);
  r.cam.z = ctx.near;
  r.pixel = ctx.projector.to_pixel(r.cam);
  return r;
}

bool finite2(glm::dvec2 p) { return std::isfinite(p.x) && std::isfinite(p.y); }

SetupTriangle setup_triangle(std::size_t t, const BuildContext& ctx) {
  SetupTriangle s;
  const MeshTables& tables = *ctx.tables;
  const std::size_t m =
      std::size_t(std::upper_bound(tables.triangle_begin.begin(), tables.triangle_begin.end(), t) -
                  tables.triangle_begin.begin()) -
      1;
  const TriangleMesh& mesh = *(*tables.meshes)[m];
  const glm::uvec3 idx = mesh.triangles[t - tables.triangle_begin[m]];
  const CameraVertex* base = ctx.vertices + tables.vertex_begin[m];
  const CameraVertex* const* v = s.vertex;
  s.vertex[0] = base + idx.x;
  s.vertex[1] = base + idx.y;
  s.vertex[2] = base + idx.z;
  s.position[0] = &mesh.positions[idx.x];
  s.position[1] = &mesh.positions[idx.y];
  s.position[2] = &mesh.positions[idx.z];
  s.object = std::uint16_t(m);
  if (!tables.corner_normals->empty() && (*tables.corner_normals)[m] != nullptr) {
    s.corner_normals = (*tables.corner_normals)[m]->data() + 3 * (t - tables.triangle_begin[m]);
  }

  const int inside = int(v[0]->cam.z >= ctx.near) + int(v[1]->cam.z >= ctx.near) + int(v[2]->cam.z >= ctx.near);
  if (inside == 0) return s;

  // Sutherland-Hodgman against z >= near; the polygon keeps the winding.
  glm::dvec2 polygon[4];
  int count = 0;
  for (int i = 0; i < 3; ++i) {
    const CameraVertex& a = *v[i];
    const CameraVertex& b = *v[(i + 1) % 3];
    const bool a_in = a.cam.z >= ctx.near, b_in = b.cam.z >= ctx.near;
    if (a_in) polygon[count++] = a.pixel;
    if (a_in != b_in) polygon[count++] = (a_in ? clip_point(a, b, ctx) : clip_point(b, a, ctx)).pixel;
  }
  for (int i = 0; i < count; ++i) {
    if (!finite2(polygon[i])) return s;  // non-finite input positions
  }
  s.piece[0][0] = polygon[0];
  s.piece[0][1] = polygon[1];
  s.piece[0][2] = polygon[2];
  s.pieces = 1;
  if (count == 4) {
    s.piece[1][0] = polygon[0];
    s.piece[1][1] = polygon[2];
    s.piece[1][2] = polygon[3];
    s.pieces = 2;
  }
  return s;
}

// Pixel rows [y0, y1] and columns [x0, x1] whose centres may be covered by
// the triangle (centres on the boundary included); empty when y0 > y1.
struct PixelRect {
  int x0, y0, x1, y1;
};

PixelRect pixel_rect(const glm::dvec2* p, int width, int height) {
  const double lo_x = std::min({p[0].x, p[1].x, p[2].x}), hi_x = std::max({p[0].x, p[1].x, p[2].x});
  const double lo_y = std::min({p[0].y, p[1].y, p[2].y}), hi_y = std::max({p[0].y, p[1].y, p[2].y});
  // Centre c = i + 0.5 lies in [lo, hi] for i in [ceil(lo - 0.5), floor(hi - 0.5)]; clamp before int.
  auto first = [](double lo, int n) { return int(std::clamp(std::ceil(lo - 0.5), 0.0, double(n))); };
  auto last = [](double hi, int n) { return int(std::clamp(std::floor(hi - 0.5), -1.0, double(n - 1))); };
  return PixelRect{first(lo_x, width), first(lo_y, height), last(hi_x, width), last(hi_y, height)};
}

// The shading normal at camera-space point c of the triangle: its corner
// normals weighted by c's barycentric coordinates (clamped to the triangle,
// which c leaves only by rounding), renormalised; the geometric normal where
// that fails or points to the inner side.
vec3 shading_normal(const SetupTriangle& s, const TriangleAttributes& a, dvec3 c) {
  const dvec3 &c0 = s.vertex[0]->cam, &c1 = s.vertex[1]->cam, &c2 = s.vertex[2]->cam;
  const dvec3& n = a.plane_normal;  // cross(c1 - c0, c2 - c0)
  const double nn = glm::dot(n, n);
  if (!(nn > 0.0)) return a.world_normal;
  const dvec3 d = c - c0;
  double b1 = std::max(glm::dot(glm::cross(d, c2 - c0), n) / nn, 0.0);
  double b2 = std::max(glm::dot(glm::cross(c1 - c0, d), n) / nn, 0.0);
  double b0 = std::max(1.0 - b1 - b2, 0.0);
  const double sum = b0 + b1 + b2;
  b0 /= sum;
  b1 /= sum;
  b2 /= sum;
  const dvec3 interpolated = b0 * dvec3(s.corner_normals[0]) + b1 * dvec3(s.corner_normals[1]) +
                             b2 * dvec3(s.corner_normals[2]);
  const double length = glm::length(interpolated);
  if (!(length > 0.0) || !std::isfinite(length)) return a.world_normal;
  const vec3 result(interpolated / length);
  return glm::dot(result, a.world_normal) > 0.0f ? result : a.world_normal;
}

// Rasterises triangle t's rows inside [row0, row1]. Counting (fragments ==
// nullptr) adds to `counts`; filling writes at offsets[i] + counts[i] and
// advances counts[i], never past offsets[i + 1]. One function serves both
// passes so they make bit-identical coverage decisions.
void raster_triangle(std::size_t t, const BuildContext& ctx, int row0, int row1, std::uint32_t* counts,
                     const std::uint32_t* offsets, LdiFragment* fragments) {
  const SetupTriangle s = setup_triangle(t, ctx);
  TriangleAttributes a;
  bool have_attributes = false;
  for (int k = 0; k < s.pieces; ++k) {
    const glm::dvec2* p = s.piece[k];
    const Edge edges[3] = {make_edge(p[0], p[1]), make_edge(p[1], p[2]), make_edge(p[2], p[0])};
    if (edges[0].tie == 0 || edges[1].tie == 0 || edges[2].tie == 0) continue;  // a point, no area
    const PixelRect r = pixel_rect(p, ctx.width, ctx.height);
    const int y_begin = std::max(r.y0, row0), y_end = std::min(r.y1, row1);
    for (int y = y_begin; y <= y_end; ++y) {
      const double py = double(y) + 0.5;
      const double row_term[3] = {edges[0].dx * (py - edges[0].ay), edges[1].dx * (py - edges[1].ay),
                                  edges[2].dx * (py - edges[2].ay)};
      for (int x = r.x0; x <= r.x1; ++x) {
        const double px = double(x) + 0.5;
        const int s0 = edge_side(edges[0], row_term[0], px);
        if (edge_side(edges[1], row_term[1], px) != s0 || edge_side(edges[2], row_term[2], px) != s0) continue;
        const std::size_t i = std::size_t(x) + std::size_t(ctx.width) * std::size_t(y);
        if (fragments == nullptr) {
          ++counts[i];
          continue;
        }
        const std::uint32_t slot = offsets[i] + counts[i];
        if (slot >= offsets[i + 1]) continue;  // cannot happen: same decisions as the counting pass
        ++counts[i];
        const glm::dvec2 uv = ctx.projector.image_plane(px, py);
        if (!have_attributes) {
          a = attributes(s);
          have_attributes = true;
        }
        const dvec3& n = a.plane_normal;
        const double depth = ctx.projector.orthographic
                                 ? (a.plane_offset - n.x * uv.x - n.y * uv.y) / n.z
                                 : a.plane_offset / (n.x * uv.x + n.y * uv.y + n.z);
        // Counter-clockwise from outside is clockwise in y-down pixel space:
        // a front face has its inside at negative edge values.
        vec3 normal = a.world_normal;
        if (s.corner_normals != nullptr) {
          const dvec3 hit = ctx.projector.orthographic ? dvec3(uv.x, uv.y, depth) : depth * dvec3(uv.x, uv.y, 1.0);
          normal = shading_normal(s, a, hit);
        }
        fragments[slot] = LdiFragment{float(depth), normal, s.object, s0 < 0};
      }
    }
  }
}

void sort_pixel(LdiFragment* f, std::uint32_t n) {
  auto closer = [](const LdiFragment& a, const LdiFragment& b) { return a.depth < b.depth; };
  if (n > 24) {
    std::sort(f, f + n, closer);
  } else {
    for (std::uint32_t i = 1; i < n; ++i) {
      const LdiFragment v = f[i];
      std::uint32_t j = i;
      for (; j > 0 && closer(v, f[j - 1]); --j) f[j] = f[j - 1];
      f[j] = v;
    }
  }
  // Where a ray passes exactly through an edge on a silhouette, both of its
  // triangles are crossed at the same point and the two depths differ only by
  // rounding; put such a pair in the order the mesh's parity asks for (after
  // a leaving crossing comes an entering one; with no earlier crossing of the
  // mesh, entering first, as for a camera outside it).
  for (std::uint32_t i = 0; i + 1 < n; ++i) {
    LdiFragment& a = f[i];
    LdiFragment& b = f[i + 1];
    if (a.object != b.object || a.entering == b.entering) continue;
    if (std::abs(b.depth - a.depth) > 1e-5f * std::max(std::abs(a.depth), std::abs(b.depth))) continue;
    bool expect_entering = true;
    for (std::uint32_t j = i; j-- > 0;) {
      if (f[j].object == a.object) {
        expect_entering = !f[j].entering;
        break;
      }
    }
    if (a.entering != expect_entering) std::swap(a, b);
  }
}

}  // namespace

void LayeredDepthImage::build(const std::vector<const TriangleMesh*>& meshes_world, const CameraView& camera,
                              int width, int height) {
  build(meshes_world, {}, camera, width, height);
}

void LayeredDepthImage::build(const std::vector<const TriangleMesh*>& meshes_world,
                              const std::vector<const std::vector<vec3>*>& corner_normals, const CameraView& camera,
                              int width, int height) {
  if (width <= 0 || height <= 0) {
    throw InvalidArgument("width", "layered depth image size must be positive, got " + std::to_string(width) +
                                       " x " + std::to_string(height));
  }
  if (meshes_world.size() > std::size_t(std::numeric_limits<std::uint16_t>::max()) + 1) {
    throw InvalidArgument("meshes", "at most 65536 meshes fit the 16-bit object id, got " +
                                        std::to_string(meshes_world.size()));
  }
  // A failed build leaves an empty image (storage kept for the next one).
  width_ = height_ = 0;
  offsets_.clear();
  fragments_.clear();

  MeshTables tables;
  tables.meshes = &meshes_world;
  tables.corner_normals = &corner_normals;
  if (!corner_normals.empty() && corner_normals.size() != meshes_world.size()) {
    throw InvalidArgument("corner_normals", "must be empty or have one entry per mesh (" +
                                                std::to_string(meshes_world.size()) + "), got " +
                                                std::to_string(corner_normals.size()));
  }
  tables.triangle_begin.assign(1, 0);
  tables.vertex_begin.assign(1, 0);
  for (std::size_t m = 0; m < meshes_world.size(); ++m) {
    const TriangleMesh* mesh = meshes_world[m];
    const std::string name = "meshes[" + std::to_string(m) + "]";
    if (mesh == nullptr) throw InvalidArgument(name, "is null");
    const std::size_t vertex_count = mesh->positions.size();
    for (std::size_t t = 0; t < mesh->triangles.size(); ++t) {
      const glm::uvec3 idx = mesh->triangles[t];
      if (idx.x >= vertex_count || idx.y >= vertex_count || idx.z >= vertex_count) {
        throw InvalidArgument(name, "triangle " + std::to_string(t) + " has a vertex index out of range (" +
                                        std::to_string(vertex_count) + " positions)");
      }
    }
    if (!corner_normals.empty() && corner_normals[m] != nullptr &&
        corner_normals[m]->size() != 3 * mesh->triangles.size()) {
      throw InvalidArgument("corner_normals[" + std::to_string(m) + "]",
                            "must hold 3 normals per triangle (" + std::to_string(3 * mesh->triangles.size()) +
                                "), got " + std::to_string(corner_normals[m]->size()));
    }
    tables.triangle_begin.push_back(tables.triangle_begin.back() + mesh->triangles.size());
    tables.vertex_begin.push_back(tables.vertex_begin.back() + vertex_count);
  }
  const std::size_t triangle_count = tables.triangle_begin.back();
  const std::size_t vertex_count = tables.vertex_begin.back();
  if (triangle_count > std::numeric_limits<std::uint32_t>::max()) {
    throw InvalidArgument("meshes", "more than 2^32 - 1 triangles in all: " + std::to_string(triangle_count));
  }
  const std::uint64_t pixels = std::uint64_t(width) * std::uint64_t(height);
  const int bands = (height + kBandRows - 1) / kBandRows;

  // Scratch: projected vertices, per-triangle band ranges, band bins, and the
  // per-pixel offsets and fill cursors.
  check_memory_budget(
      "layered depth image",
      checked_product({pixels + 1, 2 * sizeof(std::uint32_t)}) + vertex_count * sizeof(CameraVertex) +
          triangle_count * (2 * sizeof(std::int32_t) + 2 * sizeof(std::uint32_t)));

  BuildContext ctx;
  ctx.tables = &tables;
  ctx.width = width;
  ctx.height = height;
  Projector& pr = ctx.projector;
  pr.eye = dvec3(camera.eye);
  pr.right = dvec3(camera.right);
  pr.up = dvec3(camera.up);
  pr.forward = dvec3(camera.forward);
  pr.half_height = double(camera.half_height);
  pr.half_width = pr.half_height * double(width) / double(height);
  pr.width = double(width);
  pr.height = double(height);
  pr.orthographic = camera.orthographic;

  std::vector<CameraVertex> vertices(vertex_count);
  for (std::size_t m = 0; m < meshes_world.size(); ++m) {
    const std::vector<vec3>& positions = meshes_world[m]->positions;
    CameraVertex* out = vertices.data() + tables.vertex_begin[m];
    parallel_for(0, std::int64_t(positions.size()), [&](std::int64_t first, std::int64_t last) {
      for (std::int64_t i = first; i < last; ++i) {
        out[i].cam = pr.to_camera(positions[std::size_t(i)]);
        if (pr.orthographic || out[i].cam.z > 0.0) out[i].pixel = pr.to_pixel(out[i].cam);
      }
    }, 4096);
  }
  double farthest = 0.0;
  for (const CameraVertex& v : vertices) farthest = std::max(farthest, v.cam.z);
  ctx.near = pr.orthographic ? 0.0 : kNearFraction * (farthest > 0.0 ? farthest : 1.0);
  ctx.vertices = vertices.data();

  // Bands of rows each triangle may cover, then the triangles of each band.
  std::vector<std::int32_t> band_range(2 * triangle_count);
  parallel_for(0, std::int64_t(triangle_count), [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t t = first; t < last; ++t) {
      const SetupTriangle s = setup_triangle(std::size_t(t), ctx);
      int lo = height, hi = -1;
      for (int k = 0; k < s.pieces; ++k) {
        const PixelRect r = pixel_rect(s.piece[k], width, height);
        if (r.x0 > r.x1 || r.y0 > r.y1) continue;
        lo = std::min(lo, r.y0);
        hi = std::max(hi, r.y1);
      }
      band_range[2 * std::size_t(t)] = lo <= hi ? lo / kBandRows : 1;
      band_range[2 * std::size_t(t) + 1] = lo <= hi ? hi / kBandRows : 0;
    }
  }, 1024);
  std::vector<std::uint64_t> bin_begin(std::size_t(bands) + 1, 0);
  for (std::size_t t = 0; t < triangle_count; ++t) {
    for (std::int32_t b = band_range[2 * t]; b <= band_range[2 * t + 1]; ++b) ++bin_begin[std::size_t(b) + 1];
  }
  for (int b = 0; b < bands; ++b) bin_begin[std::size_t(b) + 1] += bin_begin[std::size_t(b)];
  check_memory_budget("layered depth image triangle bins", checked_product({bin_begin.back(), sizeof(std::uint32_t)}));
  std::vector<std::uint32_t> bins(bin_begin.back());
  {
    std::vector<std::uint64_t> fill(bin_begin.begin(), bin_begin.end() - 1);
    for (std::size_t t = 0; t < triangle_count; ++t) {
      for (std::int32_t b = band_range[2 * t]; b <= band_range[2 * t + 1]; ++b) {
        bins[fill[std::size_t(b)]++] = std::uint32_t(t);
      }
    }
  }

  auto for_each_band = [&](const std::function<void(int band, int row0, int row1)>& body) {
    parallel_for(0, bands, [&](std::int64_t first, std::int64_t last) {
      for (std::int64_t b = first; b < last; ++b) {
        body(int(b), int(b) * kBandRows, std::min(int(b) * kBandRows + kBandRows, height) - 1);
      }
    });
  };

  // Pass 1: fragments per pixel, turned into offsets by a prefix sum.
  offsets_.assign(std::size_t(pixels) + 1, 0);
  for_each_band([&](int band, int row0, int row1) {
    for (std::uint64_t k = bin_begin[std::size_t(band)]; k < bin_begin[std::size_t(band) + 1]; ++k) {
      raster_triangle(bins[k], ctx, row0, row1, offsets_.data(), nullptr, nullptr);
    }
  });
  std::uint64_t total = 0;
  for (std::size_t i = 0; i < pixels; ++i) {
    const std::uint32_t n = offsets_[i];
    offsets_[i] = std::uint32_t(std::min<std::uint64_t>(total, std::numeric_limits<std::uint32_t>::max()));
    total += n;
  }
  const std::uint64_t fragment_bytes = checked_product({total, sizeof(LdiFragment)});
  check_memory_budget("layered depth image fragments",
                      fragment_bytes + checked_product({pixels + 1, 2 * sizeof(std::uint32_t)}));
  if (total > std::numeric_limits<std::uint32_t>::max()) {
    throw OutOfMemoryBudget("layered depth image fragments (32-bit offsets)", fragment_bytes,
                            std::uint64_t(std::numeric_limits<std::uint32_t>::max()) * sizeof(LdiFragment));
  }
  offsets_[pixels] = std::uint32_t(total);

  // Pass 2: fill, then sort each pixel of the band front to back.
  fragments_.resize(std::size_t(total));
  std::vector<std::uint32_t> cursor(std::size_t(pixels), 0);
  for_each_band([&](int band, int row0, int row1) {
    for (std::uint64_t k = bin_begin[std::size_t(band)]; k < bin_begin[std::size_t(band) + 1]; ++k) {
      raster_triangle(bins[k], ctx, row0, row1, cursor.data(), offsets_.data(), fragments_.data());
    }
    const std::size_t first = std::size_t(row0) * std::size_t(width);
    const std::size_t last = std::size_t(row1 + 1) * std::size_t(width);
    for (std::size_t i = first; i < last; ++i) {
      sort_pixel(fragments_.data() + offsets_[i], offsets_[i + 1] - offsets_[i]);
    }
  });
  width_ = width;
  height_ = height;
}

LdiView LayeredDepthImage::view() const {
  return LdiView{offsets_.empty() ? nullptr : offsets_.data(), fragments_.data(), width_, height_};
}

std::uint64_t LayeredDepthImage::bytes() const {
  return std::uint64_t(offsets_.size()) * sizeof(std::uint32_t) +
         std::uint64_t(fragments_.size()) * sizeof(LdiFragment);
}

std::vector<vec3> smooth_corner_normals(const TriangleMesh& mesh, float crease_deg) {
  const std::size_t vertex_count = mesh.positions.size(), triangle_count = mesh.triangles.size();
  const std::vector<std::uint32_t> weld = mesh.welded_indices();
  // Per triangle: cross product (twice the area along the normal) and unit normal.
  std::vector<dvec3> weighted(triangle_count), unit(triangle_count, dvec3(0.0));
  for (std::size_t t = 0; t < triangle_count; ++t) {
    const glm::uvec3 idx = mesh.triangles[t];
    const dvec3 p0(mesh.positions[idx.x]), p1(mesh.positions[idx.y]), p2(mesh.positions[idx.z]);
    weighted[t] = glm::cross(p1 - p0, p2 - p0);
    const double length = glm::length(weighted[t]);
    if (length > 0.0 && std::isfinite(length)) unit[t] = weighted[t] / length;
    else weighted[t] = dvec3(0.0);
  }
  // Triangles around each welded vertex (CSR).
  std::vector<std::uint32_t> begin(vertex_count + 1, 0), around(3 * triangle_count);
  for (const glm::uvec3& idx : mesh.triangles) {
    for (int k = 0; k < 3; ++k) ++begin[weld[idx[k]] + 1];
  }
  for (std::size_t v = 0; v < vertex_count; ++v) begin[v + 1] += begin[v];
  {
    std::vector<std::uint32_t> fill(begin.begin(), begin.end() - 1);
    for (std::size_t t = 0; t < triangle_count; ++t) {
      for (int k = 0; k < 3; ++k) around[fill[weld[mesh.triangles[t][k]]]++] = std::uint32_t(t);
    }
  }
  const double min_cos = std::cos(double(crease_deg) * double(kPi) / 180.0);
  std::vector<vec3> normals(3 * triangle_count, vec3(0.0f));
  for (std::size_t t = 0; t < triangle_count; ++t) {
    if (unit[t] == dvec3(0.0)) continue;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = weld[mesh.triangles[t][k]];
      dvec3 sum(0.0);
      for (std::uint32_t j = begin[v]; j < begin[v + 1]; ++j) {
        const std::uint32_t u = around[j];
        if (glm::dot(unit[t], unit[u]) >= min_cos) sum += weighted[u];
      }
      const double length = glm::length(sum);
      normals[3 * t + std::size_t(k)] = length > 0.0 ? vec3(sum / length) : vec3(unit[t]);
    }
  }
  return normals;
}

}  // namespace penumbra

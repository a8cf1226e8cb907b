#pragma once
// A bounding volume hierarchy over one closed triangle mesh, for rays that
// must know where they are inside it: every crossing of the ray with the
// surface, not only the nearest (the path tracer's mesh media,
// techniques/pathtrace/mesh_media.h). Written here rather than taken from
// Embree (Debian's libembree-dev) because the query runs in PENUMBRA_HD
// kernels over plain views, on the CPU and in a CUDA build alike
// (docs/DESIGN-NOTES.md, "Mesh ray queries").
//
// Build: top-down, each node split at the median centroid along the longest
// axis of its centroids' bounds, leaves of at most 4 triangles (no surface
// area heuristic: the query visits every node a ray overlaps anyway, since it
// wants all crossings). Query: an explicit stack, Moller-Trumbore per
// triangle. A ray that passes exactly through an edge or a vertex may count
// it twice or not at all; for the random rays of a path tracer that has
// probability zero in exact arithmetic and is rare in float.
#include "penumbra/base/ray.h"
#include "penumbra/scene/mesh.h"

#include <cstdint>
#include <vector>

namespace penumbra {

struct BvhNode {
  vec3 lower{0.0f};
  std::int32_t first = 0;  // leaf: the first triangle; inner: the right child (the left one follows the node)
  vec3 upper{0.0f};
  std::int32_t count = 0;  // leaf: triangles (> 0); inner: 0
};

struct BvhTriangle {
  vec3 a{0.0f}, ab{0.0f}, ac{0.0f};  // a corner and the two edges from it
};

inline constexpr int kBvhStackDepth = 64;

struct MeshBvhView {
  const BvhNode* nodes = nullptr;
  const BvhTriangle* triangles = nullptr;
  int node_count = 0;
  int triangle_count = 0;

  // The ray parameters t in (t_min, t_max) where o + t d crosses the
  // surface, into `hits` (unsorted, at most `capacity`); returns how many
  // crossings there are, which may exceed `capacity`.
  PENUMBRA_HD int crossings(const Ray& ray, float t_min, float t_max, float* hits, int capacity) const {
    if (node_count == 0) return 0;
    const vec3 inv(1.0f / ray.direction.x, 1.0f / ray.direction.y, 1.0f / ray.direction.z);
    int stack[kBvhStackDepth];
    int top = 0;
    stack[top++] = 0;
    int found = 0;
    while (top > 0) {
      const BvhNode& node = nodes[stack[--top]];
      const vec3 t0 = (node.lower - ray.origin) * inv, t1 = (node.upper - ray.origin) * inv;
      const vec3 near = glm::min(t0, t1), far = glm::max(t0, t1);
      const float enter = glm::max(glm::max(near.x, near.y), glm::max(near.z, t_min));
      const float leave = glm::min(glm::min(far.x, far.y), glm::min(far.z, t_max));
      if (!(enter <= leave)) continue;  // also false for NaN (a zero direction component on a slab face)
      if (node.count > 0) {
        for (int i = node.first; i < node.first + node.count; ++i) {
          const float t = crossing(triangles[i], ray);
          if (t > t_min && t < t_max) {
            if (found < capacity) hits[found] = t;
            ++found;
          }
        }
      } else if (top + 2 <= kBvhStackDepth) {
        stack[top++] = node.first;
        stack[top++] = int(&node - nodes) + 1;
      }
    }
    return found;
  }

  // Moller-Trumbore: the ray parameter of the crossing with one triangle,
  // or -1.
  PENUMBRA_HD static float crossing(const BvhTriangle& tri, const Ray& ray) {
    const vec3 p = glm::cross(ray.direction, tri.ac);
    const float det = glm::dot(tri.ab, p);
    if (glm::abs(det) < 1e-12f) return -1.0f;
    const float inv_det = 1.0f / det;
    const vec3 s = ray.origin - tri.a;
    const float u = glm::dot(s, p) * inv_det;
    if (u < 0.0f || u > 1.0f) return -1.0f;
    const vec3 q = glm::cross(s, tri.ab);
    const float v = glm::dot(ray.direction, q) * inv_det;
    if (v < 0.0f || u + v > 1.0f) return -1.0f;
    return glm::dot(tri.ac, q) * inv_det;
  }
};

class MeshBvh {
 public:
  MeshBvh() = default;
  explicit MeshBvh(const TriangleMesh& mesh);
  MeshBvhView view() const {
    return MeshBvhView{nodes_.data(), triangles_.data(), int(nodes_.size()), int(triangles_.size())};
  }
  std::uint64_t bytes() const { return nodes_.size() * sizeof(BvhNode) + triangles_.size() * sizeof(BvhTriangle); }
  int depth() const { return depth_; }

 private:
  std::vector<BvhNode> nodes_;
  std::vector<BvhTriangle> triangles_;
  int depth_ = 0;
};

}  // namespace penumbra

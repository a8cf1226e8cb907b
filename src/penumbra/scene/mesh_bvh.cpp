#include "penumbra/scene/mesh_bvh.h"

#include <algorithm>
#include <numeric>

namespace penumbra {
namespace {

constexpr int kLeafTriangles = 4;

struct Builder {
  const TriangleMesh& mesh;
  std::vector<vec3> centroids;
  std::vector<std::uint32_t> order;
  std::vector<BvhNode>& nodes;
  int depth = 0;

  Box3 bounds(std::size_t first, std::size_t last) const {
    Box3 b{vec3(kInfinity), vec3(-kInfinity)};
    for (std::size_t i = first; i < last; ++i) {
      const glm::uvec3 t = mesh.triangles[order[i]];
      for (int c = 0; c < 3; ++c) {
        b.lower = glm::min(b.lower, mesh.positions[t[c]]);
        b.upper = glm::max(b.upper, mesh.positions[t[c]]);
      }
    }
    return b;
  }

  // Builds the node for order[first, last) at nodes[index] and its subtree after it.
  void build(std::size_t index, std::size_t first, std::size_t last, int level) {
    depth = std::max(depth, level + 1);
    const Box3 b = bounds(first, last);
    nodes[index].lower = b.lower;
    nodes[index].upper = b.upper;
    if (last - first <= std::size_t(kLeafTriangles)) {
      nodes[index].first = std::int32_t(first);
      nodes[index].count = std::int32_t(last - first);
      return;
    }
    Box3 c{vec3(kInfinity), vec3(-kInfinity)};
    for (std::size_t i = first; i < last; ++i) {
      c.lower = glm::min(c.lower, centroids[order[i]]);
      c.upper = glm::max(c.upper, centroids[order[i]]);
    }
    const vec3 e = c.extent();
    const int axis = e.x >= e.y && e.x >= e.z ? 0 : (e.y >= e.z ? 1 : 2);
    const std::size_t middle = first + (last - first) / 2;
    std::nth_element(order.begin() + std::ptrdiff_t(first), order.begin() + std::ptrdiff_t(middle),
                     order.begin() + std::ptrdiff_t(last), [&](std::uint32_t a, std::uint32_t b) {
                       return centroids[a][axis] < centroids[b][axis];
                     });
    nodes.emplace_back();  // the left child follows its parent
    build(index + 1, first, middle, level + 1);
    const std::size_t right = nodes.size();
    nodes.emplace_back();
    nodes[index].first = std::int32_t(right);
    nodes[index].count = 0;
    build(right, middle, last, level + 1);
  }
};

}  // namespace

MeshBvh::MeshBvh(const TriangleMesh& mesh) {
  const std::size_t n = mesh.triangles.size();
  if (n == 0) return;
  Builder b{mesh, std::vector<vec3>(n), std::vector<std::uint32_t>(n), nodes_};
  for (std::size_t i = 0; i < n; ++i) {
    const glm::uvec3 t = mesh.triangles[i];
    b.centroids[i] = (mesh.positions[t.x] + mesh.positions[t.y] + mesh.positions[t.z]) / 3.0f;
  }
  std::iota(b.order.begin(), b.order.end(), 0u);
  nodes_.reserve(2 * n / std::size_t(kLeafTriangles) + 2);
  nodes_.emplace_back();
  b.build(0, 0, n, 0);
  depth_ = b.depth;
  triangles_.reserve(n);
  for (std::uint32_t i : b.order) {
    const glm::uvec3 t = mesh.triangles[i];
    const vec3 a = mesh.positions[t.x];
    triangles_.push_back(BvhTriangle{a, mesh.positions[t.y] - a, mesh.positions[t.z] - a});
  }
}

}  // namespace penumbra

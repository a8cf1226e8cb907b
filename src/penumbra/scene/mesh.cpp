// TriangleMesh bounds and validation. MeshObject's transforms live with the
// scene code that places meshes.
#include "penumbra/scene/mesh.h"

#include "penumbra/base/error.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <unordered_map>
#include <utility>

namespace penumbra {

Box3 TriangleMesh::bounds() const {
  Box3 box;
  box.lower = vec3(std::numeric_limits<float>::infinity());
  box.upper = vec3(-std::numeric_limits<float>::infinity());
  for (const vec3& p : positions) {
    box.lower = glm::min(box.lower, p);
    box.upper = glm::max(box.upper, p);
  }
  return box;
}

void TriangleMesh::validate(const std::string& name) const {
  if (triangles.empty()) throw InvalidArgument(name, "the mesh has no triangles");
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const vec3& p = positions[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
      throw InvalidArgument(name, fmt::format("vertex {} is not finite ({}, {}, {})", i, p.x, p.y, p.z));
    }
  }
  const std::size_t count = positions.size();
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const glm::uvec3& tri = triangles[t];
    for (int k = 0; k < 3; ++k) {
      if (tri[k] >= count) {
        throw InvalidArgument(name, fmt::format("triangle {} refers to vertex {}, but the mesh has {} vertices", t,
                                                tri[k], count));
      }
    }
  }
  check_closed(name);
}

// Closed and consistently wound means every directed edge (a, b) is matched by
// as many (b, a): then every ray crosses the surface an even number of times
// and its crossings alternate between entering and leaving. Vertices at the
// same position count as one (files often split vertices at UV or normal
// seams; the rasteriser projects equal positions to equal points, so such a
// mesh is closed for the parity test too).
std::vector<std::uint32_t> TriangleMesh::welded_indices() const {
  std::unordered_map<std::uint64_t, std::uint32_t> first_at;
  first_at.reserve(positions.size());
  std::vector<std::uint32_t> weld(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const vec3 p = positions[i] + vec3(0.0f);  // -0 becomes +0, so both hash alike
    std::uint32_t bits[3];
    std::memcpy(bits, &p, sizeof(bits));
    std::uint64_t h = 1469598103934665603ULL;  // FNV-1a over the three floats' bits
    for (std::uint32_t b : bits) h = (h ^ b) * 1099511628211ULL;
    // A hash collision of different positions keeps its own index.
    auto [it, inserted] = first_at.try_emplace(h, std::uint32_t(i));
    weld[i] = (!inserted && positions[it->second] == positions[i]) ? it->second : std::uint32_t(i);
  }
  return weld;
}

void TriangleMesh::check_closed(const std::string& name) const {
  const std::vector<std::uint32_t> weld = welded_indices();
  std::vector<std::pair<std::uint32_t, std::uint32_t>> forward, backward;
  forward.reserve(3 * triangles.size());
  backward.reserve(3 * triangles.size());
  for (const glm::uvec3& t : triangles) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = weld[t[k]], b = weld[t[(k + 1) % 3]];
      if (a == b) continue;  // a degenerate edge crosses nothing
      forward.emplace_back(a, b);
      backward.emplace_back(b, a);
    }
  }
  std::sort(forward.begin(), forward.end());
  std::sort(backward.begin(), backward.end());
  const auto mismatch = std::mismatch(forward.begin(), forward.end(), backward.begin(), backward.end());
  if (mismatch.first != forward.end() || mismatch.second != backward.end()) {
    const auto edge = mismatch.first != forward.end() ? *mismatch.first : *mismatch.second;
    throw InvalidArgument(name, fmt::format("the mesh is not closed and consistently wound: the edge between vertices "
                                            "{} and {} is not matched by one running the other way (a mesh must "
                                            "bound a volume for the inside/outside test)",
                                            edge.first, edge.second));
  }
}

}  // namespace penumbra

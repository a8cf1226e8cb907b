// TriangleMesh bounds and validation. MeshObject's transforms live with the
// scene code that places meshes.
#include "penumbra/scene/mesh.h"

#include "penumbra/base/error.h"

#include <fmt/format.h>

#include <cmath>
#include <limits>

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
}

}  // namespace penumbra

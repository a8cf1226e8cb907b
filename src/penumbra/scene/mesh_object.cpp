#include "penumbra/scene/mesh.h"

#include <glm/gtc/matrix_transform.hpp>

namespace penumbra {

mat4 MeshObject::object_to_world() const {
  mat4 m = glm::translate(mat4(1.0f), translate);
  m = glm::rotate(m, glm::radians(rotate_deg.z), vec3(0.0f, 0.0f, 1.0f));
  m = glm::rotate(m, glm::radians(rotate_deg.y), vec3(0.0f, 1.0f, 0.0f));
  m = glm::rotate(m, glm::radians(rotate_deg.x), vec3(1.0f, 0.0f, 0.0f));
  return glm::scale(m, scale);
}

Box3 MeshObject::world_bounds() const {
  Box3 box{vec3(kInfinity), vec3(-kInfinity)};
  if (!mesh) return box;
  const mat4 m = object_to_world();
  for (const vec3& p : mesh->positions) {
    const vec3 w(m * vec4(p, 1.0f));
    box.lower = glm::min(box.lower, w);
    box.upper = glm::max(box.upper, w);
  }
  return box;
}

}  // namespace penumbra

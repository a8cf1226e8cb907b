#pragma once
// Opaque diffuse planes: receivers of shadows such as a floor. A plane's
// colour is the radiance a directional light of intensity 1 gives it at
// normal incidence (so a white plane and a white isotropic medium look alike
// under the same light); physically it is Lambertian with albedo colour / 4
// (DESIGN-NOTES.md "Light units"). Planes also block light: a point on the
// far side of a plane from a light is in its shadow.
#include "penumbra/base/math.h"
#include "penumbra/base/ray.h"

namespace penumbra {

struct Plane {
  vec3 point{0.0f};
  vec3 normal{0.0f, 0.0f, 1.0f};  // unit
  vec3 color{0.8f};
};

// Ray parameter of the hit in (t_min, t_max), or +inf when there is none.
PENUMBRA_HD inline float intersect_plane(const Ray& ray, const Plane& plane, float t_min, float t_max) {
  const float denom = glm::dot(ray.direction, plane.normal);
  if (denom == 0.0f) return kInfinity;
  const float t = glm::dot(plane.point - ray.origin, plane.normal) / denom;
  return (t > t_min && t < t_max) ? t : kInfinity;
}

}  // namespace penumbra

#pragma once
// Lights. Units: a light's intensity is chosen so that a white, fully
// scattering isotropic medium lit head-on by a directional light of intensity
// 1 has radiance 1 (DESIGN-NOTES.md "Light units"); physically its irradiance
// is 4 pi * intensity * colour. A point light falls off as 1 / distance^2.
#include "penumbra/base/math.h"

namespace penumbra {

enum class LightType : std::uint8_t { Directional, Point };

struct Light {
  LightType type = LightType::Directional;
  vec3 direction{0.0f, 0.0f, -1.0f};  // directional: the way the light travels (unit)
  vec3 position{0.0f};                // point light position in world units
  vec3 color{1.0f};
  float intensity = 1.0f;
};

// What a scattering point sees of a light, before occlusion.
struct LightSample {
  vec3 to_light;     // unit vector from the point toward the light
  float distance;    // to the light; +inf for a directional light
  vec3 radiance;     // colour * intensity, with 1 / d^2 for point lights
};

PENUMBRA_HD inline LightSample sample_light(const Light& light, vec3 p) {
  if (light.type == LightType::Point) {
    const vec3 d = light.position - p;
    const float dist2 = glm::max(glm::dot(d, d), 1e-12f);
    const float dist = glm::sqrt(dist2);
    return LightSample{d / dist, dist, light.color * (light.intensity / dist2)};
  }
  return LightSample{-light.direction, kInfinity, light.color * light.intensity};
}

}  // namespace penumbra

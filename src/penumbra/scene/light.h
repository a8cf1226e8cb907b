#pragma once
// Lights. Units: a light's intensity is chosen so that a white, fully
// scattering isotropic medium lit head-on by a directional light of intensity
// 1 has radiance 1 (DESIGN-NOTES.md "Light units"); physically its irradiance
// is 4 pi * intensity * colour.
//
//   directional  parallel light travelling along `direction`
//   point        at `position`, falling off as 1 / distance^2
//   distant      an area light at infinity: a cone of directions about
//                `direction` with half-angle `angle_deg` (profile uniform) or
//                angular standard deviation `angle_deg` (profile gaussian);
//                it delivers the same irradiance as a directional light of the
//                same intensity, and becomes one as the angle goes to 0
//   sphere       a sphere of `radius` at `position`, with the power of a point
//                light of the same intensity (a point light as radius -> 0)
//   disk         a one-sided disk of `radius` at `position` facing `direction`
//                (its emitting side), with the power a point light would
//                send into that hemisphere
//   environment  uniform radiance intensity * colour from every direction
//                (the white-furnace light)
//
// Techniques other than the path tracer light with the central direction or
// position of an area light (hard shadows) and leave environment lights out;
// the scene's `ambient` is their stand-in for sky light.
#include "penumbra/base/math.h"

namespace penumbra {

enum class LightType : std::uint8_t { Directional, Point, Distant, Sphere, Disk, Environment };
enum class LightProfile : std::uint8_t { Uniform, Gaussian };

struct Light {
  LightType type = LightType::Directional;
  vec3 direction{0.0f, 0.0f, -1.0f};  // directional/distant: travel direction; disk: the side it emits to (unit)
  vec3 position{0.0f};                // point/sphere/disk centre in world units
  vec3 color{1.0f};
  float intensity = 1.0f;
  float angle_deg = 0.0f;  // distant: cone half-angle (uniform) or standard deviation (gaussian)
  LightProfile profile = LightProfile::Uniform;
  float radius = 0.0f;  // sphere, disk

  PENUMBRA_HD bool at_infinity() const {
    return type == LightType::Directional || type == LightType::Distant || type == LightType::Environment;
  }
};

// What a scattering point sees of a light's centre, before occlusion.
struct LightSample {
  vec3 to_light;   // unit vector from the point toward the light
  float distance;  // to the light; +inf for lights at infinity
  vec3 radiance;   // colour * intensity, with 1 / d^2 for lights at a position
};

// The light as the single-scattering techniques see it: area lights by their
// centre. Environment lights give zero radiance here (see above).
PENUMBRA_HD inline LightSample sample_light(const Light& light, vec3 p) {
  switch (light.type) {
    case LightType::Point:
    case LightType::Sphere:
    case LightType::Disk: {
      const vec3 d = light.position - p;
      const float dist2 = glm::max(glm::dot(d, d), 1e-12f);
      const float dist = glm::sqrt(dist2);
      const vec3 to_light = d / dist;
      float scale = light.intensity / dist2;
      // A disk lights only the side it faces, with the cosine of its emission.
      if (light.type == LightType::Disk) scale *= 2.0f * glm::max(0.0f, -glm::dot(to_light, light.direction));
      return LightSample{to_light, dist, light.color * scale};
    }
    case LightType::Environment: return LightSample{vec3(0.0f, 0.0f, 1.0f), kInfinity, vec3(0.0f)};
    case LightType::Directional:
    case LightType::Distant: break;
  }
  return LightSample{-light.direction, kInfinity, light.color * light.intensity};
}

}  // namespace penumbra

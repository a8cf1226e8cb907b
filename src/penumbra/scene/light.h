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
//                same intensity, and becomes one as the angle goes to 0.
//                A gaussian one may be anisotropic: `angle_deg` is then the
//                spread along the light frame's x axis, `angle_y_deg` along
//                its y axis, both turned by `rotation_deg` (distant_light_frame
//                below; Patel et al. 2013, section 3, eq. 7)
//   sphere       a sphere of `radius` at `position`, with the power of a point
//                light of the same intensity (a point light as radius -> 0)
//   disk         a one-sided disk of `radius` at `position` facing `direction`
//                (its emitting side), with the power a point light would
//                send into that hemisphere
//   environment  uniform radiance intensity * colour from every direction
//                (the white-furnace light)
//
// Soft-shadow techniques take their softness from an area light's size (each
// technique's first file says how), the others its centre (hard shadows); all
// but pathtrace leave environment lights out (`ambient` stands in for them).
#include "penumbra/base/lanes.h"
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
  float angle_deg = 0.0f;  // distant: cone half-angle (uniform) or standard deviation (gaussian; along x)
  LightProfile profile = LightProfile::Uniform;
  float radius = 0.0f;  // sphere, disk
  // Distant gaussian only: the spread along the light frame's y axis
  // (negative: unset, the same as angle_deg, an isotropic light) and the
  // frame's rotation about the central direction, in degrees.
  float angle_y_deg = -1.0f;
  float rotation_deg = 0.0f;

  PENUMBRA_HD bool at_infinity() const {
    return type == LightType::Directional || type == LightType::Distant || type == LightType::Environment;
  }
  // The y spread in degrees, angle_deg when unset.
  PENUMBRA_HD float spread_y_deg() const { return angle_y_deg < 0.0f ? angle_deg : angle_y_deg; }
};

// The frame of a distant light whose central direction toward the light is
// the unit vector c (c = -Light::direction). Before rotation:
//   a = the unit vector perpendicular to c closest to world +x (+x made
//       orthogonal to c by Gram-Schmidt); world +y instead when c lies
//       within 1 degree of +-x, where that is ill-conditioned;
//   b = cross(c, a), so (a, b, c) is right-handed: cross(a, b) = c.
// Then both turn by rotation_deg about c by the right-hand rule: positive
// turns a toward b, counter-clockwise as seen from the light looking down
// into the scene (for a light behind a camera that looks along -c with
// right = a and up = b, counter-clockwise in the image).
// Only the line of c matters for a (Gram-Schmidt against c or -c agree).
PENUMBRA_HD inline void distant_light_frame(vec3 c, float rotation_deg, vec3& a, vec3& b) {
  const float cos_1deg = 0.99984770f;
  const vec3 seed = glm::abs(c.x) > cos_1deg ? vec3(0.0f, 1.0f, 0.0f) : vec3(1.0f, 0.0f, 0.0f);
  const vec3 a0 = glm::normalize(seed - glm::dot(seed, c) * c);
  const vec3 b0 = glm::cross(c, a0);
  const float r = glm::radians(rotation_deg);
  const float cr = glm::cos(r), sr = glm::sin(r);
  a = cr * a0 + sr * b0;
  b = -sr * a0 + cr * b0;
}

// Tangent-plane standard deviations (x, y) of a gaussian distant light on its
// virtual light plane at unit distance: (tan(angle_deg), tan(angle_y_deg)).
PENUMBRA_HD inline vec2 gaussian_light_spreads(const Light& light) {
  return vec2(glm::tan(glm::radians(light.angle_deg)), glm::tan(glm::radians(light.spread_y_deg())));
}

// What a scattering point sees of a light's centre, before occlusion, for
// one position or a packet of them (base/lanes.h).
template <class L> struct LightSampleL {
  typename L::Vec3 to_light;   // unit vector from the point toward the light
  typename L::Float distance;  // to the light; +inf for lights at infinity
  typename L::Vec3 radiance;   // colour * intensity, with 1 / d^2 for lights at a position
};
using LightSample = LightSampleL<ScalarLanes>;

// The light as the single-scattering techniques see it: area lights by their
// centre. Environment lights give zero radiance here (see above).
template <class L>
PENUMBRA_HD PENUMBRA_FORCE_INLINE LightSampleL<L> sample_light(const Light& light, const typename L::Vec3& p) {
  using F = typename L::Float;
  using V = typename L::Vec3;
  switch (light.type) {
    case LightType::Point:
    case LightType::Sphere:
    case LightType::Disk: {
      const V d = V(light.position) - p;
      const F dist2 = max(dot(d, d), F(1e-12f));
      const F dist = sqrt(dist2);
      const V to_light = d / dist;
      F scale = light.intensity / dist2;
      // A disk lights only the side it faces, with the cosine of its emission.
      if (light.type == LightType::Disk) scale *= 2.0f * max(F(0.0f), -dot(to_light, V(light.direction)));
      return LightSampleL<L>{to_light, dist, V(light.color) * scale};
    }
    case LightType::Environment: return LightSampleL<L>{V(vec3(0.0f, 0.0f, 1.0f)), F(kInfinity), V(0.0f)};
    case LightType::Directional:
    case LightType::Distant: break;
  }
  return LightSampleL<L>{V(-light.direction), F(kInfinity), V(light.color * light.intensity)};
}

PENUMBRA_HD PENUMBRA_FORCE_INLINE LightSample sample_light(const Light& light, vec3 p) {
  return sample_light<ScalarLanes>(light, p);
}

}  // namespace penumbra

#pragma once
// ipsvi's two light models (parameter light_model).
//
//   grey   (the default) what shadow-rays computes, so that the two can be
//          compared: the direct light is the grey transmittance T(s_l, s),
//          blended with the forward-scattered part T_m by one global albedo
//          a (forward_scattering.h): V = (1 - a) T + a T_m.
//   paper  Sundén et al. 2011, section 3:
//          - the direct light is Eq. 3, I_ss(s) = T(s_l, s) L +
//            integral T(s', s) tau(s') c_e(s') ds' over the light ray, with
//            c_e the (shadow) TF colour: Listing 4.1's back-to-front
//            composite of each sample's colour into the light. The light
//            takes the colour of the medium it crosses; a bright medium
//            passes its colour on however opaque it is (an opaque white
//            slab casts no shadow, a red one a red light).
//          - a(s), the probability that light is scattered rather than
//            absorbed at s, is the sample's own scattering albedo:
//            material.albedo times its TF colour per channel (DESIGN.md 1),
//            scaled by the `albedo` parameter (1: exactly the material's);
//            planes, which are not a medium, keep the parameter's a.
//            V = (1 - a(s)) I_ss + a(s) I_ms per channel (Eq. 2).
//          - p(s): the material's phase function at the sample's own light
//            and view directions, as in the grey model, for I_ss; for I_ms,
//            which arrives from anywhere in the cone Theta, its mean over
//            the cone (Eq. 2's integral of p over Theta, with I_ms spread
//            evenly over the cone), applied as the ratio of that mean to
//            the centre value, since the shading multiplies V by p
//            (lighting.h). With Phong shading there is no phase function
//            and the ratio is 1.
// The engine's material has one albedo and one phase asymmetry; a(s) varies
// with the data through the TF colour, p(s) through the directions.
#include "penumbra/base/math.h"

#include <cstdint>

namespace penumbra {

enum class IpsviLightModel : std::uint8_t { Grey, Paper };

// The cone mean of the Henyey-Greenstein phase function over its value at
// the cone's axis, tabulated over the cosine between the axis (the light's
// direction) and the direction toward the viewer.
struct ConePhase {
  static constexpr int kEntries = 64;  // intervals over cos in [-1, 1]
  float ratio[kEntries + 1];

  PENUMBRA_HD float at(float cos_angle) const {
    const float x = glm::clamp(0.5f * (cos_angle + 1.0f), 0.0f, 1.0f) * float(kEntries);
    const int i = glm::min(int(x), kEntries - 1);
    const float f = x - float(i);
    return (1.0f - f) * ratio[i] + f * ratio[i + 1];
  }
};

// g: the phase asymmetry; theta: the cone's half-angle in degrees. With
// g = 0 or theta = 0 every ratio is 1. Integrated numerically over the cone
// (uniform in solid angle).
ConePhase make_cone_phase(float g, float cone_angle_deg);

// a(s) per channel: `blend` (the albedo parameter) times the sample's
// scattering albedo, clamped to [0, 1].
PENUMBRA_HD inline vec3 paper_albedo(float blend, float material_albedo, vec3 color) {
  return blend * glm::clamp(material_albedo * color, vec3(0.0f), vec3(1.0f));
}

// Eq. 2's blend: single scattering I_ss (rgb), multiple scattering I_ms
// weighted by the cone-mean phase ratio.
PENUMBRA_HD inline vec3 paper_visibility(vec3 single, vec3 multiple, vec3 a, float phase_ratio) {
  return (vec3(1.0f) - a) * single + a * (phase_ratio * multiple);
}

}  // namespace penumbra

#pragma once
// The optical model IPSVI (Sundén et al. 2011, section 3) and half-angle
// slicing (Kniss et al. 2002/2003) share, so the two can be compared with each
// other and, at albedo 0, with shadow-rays.
//
// Light reaching a sample is a blend, by the paper's albedo a (eq. 2), of
//   direct  T_d: single scattering, the transmittance exp(-integral sigma_t)
//           toward the light (eq. 3), exactly what shadow-rays computes;
//   diffuse T_m: forward multiple scattering within a cone of half-angle theta
//           toward the light (eq. 4 and 6), modelled as Kniss et al. do it:
//           the light is attenuated only by what the medium removes from the
//           cone, and spread sideways by a low-pass filter.
// V = (1 - a) T_d + a T_m then enters the engine's shading (lighting.h) as the
// light visibility, with the scene's phase function.
//
// Choices the papers leave open, made here once for both techniques:
//  - Attenuation of T_m. A sample of scattering albedo rho = material.albedo *
//    TF colour scatters rho of what it removes, and the fraction f(theta, g)
//    of that stays inside the cone (integral of the Henyey-Greenstein phase
//    function over the cone); so T_m decays with sigma_t (1 - rho f) per
//    channel instead of sigma_t. This is IPSVI's Listing 4.1 (the sample's
//    colour is composited into the light "back to front") with the colour the
//    sample actually sends forward.
//  - The spread. Kniss et al. blur the light buffer per slice by a disk of
//    radius (slice distance) tan(theta), so the total spread depends on the
//    slice count. Both techniques here use that rule's step-independent
//    limit, a diffusion: each step of length D along the light adds variance
//    D h tan^2(theta) per axis, with h the smallest voxel spacing (as if the
//    light were deflected by up to theta once per voxel).
#include "penumbra/base/lanes.h"
#include "penumbra/base/math.h"
#include "penumbra/scene/light.h"

namespace penumbra {

// Fraction of Henyey-Greenstein scattering (asymmetry g) that leaves within
// theta of the incident direction: P(cos >= cos_theta) for the normalised HG
// phase function, (1 + g) / 2g - (1 - g^2) / (2g sqrt(1 + g^2 - 2 g cos_theta)),
// which tends to (1 - cos_theta) / 2 for isotropic scattering.
PENUMBRA_HD inline float hg_cone_fraction(float g, float cos_theta) {
  if (glm::abs(g) < 1e-4f) return 0.5f * (1.0f - cos_theta);
  const float root = glm::sqrt(glm::max(1.0f + g * g - 2.0f * g * cos_theta, 1e-12f));
  return glm::clamp((1.0f + g) / (2.0f * g) - (1.0f - g * g) / (2.0f * g * root), 0.0f, 1.0f);
}

struct ForwardScattering {
  float blend = 0.0f;             // the paper's albedo a: weight of the diffuse part
  float scattering_albedo = 1.0f;  // material.albedo
  float cone_fraction = 0.0f;     // f(theta, g)
  float spread_per_length = 0.0f;  // h tan^2(theta): variance per unit of light path (world units)

  PENUMBRA_HD bool has_diffuse() const { return blend > 0.0f; }

  // Extinction of the diffuse part for a sample of TF colour `color`.
  template <class L>
  PENUMBRA_HD typename L::Vec3 diffuse_extinction(const typename L::Vec3& color, typename L::Float sigma_t) const {
    using V = typename L::Vec3;
    return sigma_t * (V(1.0f) - min(color * scattering_albedo, V(1.0f)) * cone_fraction);
  }
  PENUMBRA_HD vec3 diffuse_extinction(vec3 color, float sigma_t) const {
    return diffuse_extinction<ScalarLanes>(color, sigma_t);
  }

  template <class L>
  PENUMBRA_HD typename L::Vec3 visibility(typename L::Float direct, const typename L::Vec3& diffuse) const {
    using V = typename L::Vec3;
    return (1.0f - blend) * V(direct) + blend * diffuse;
  }
  PENUMBRA_HD vec3 visibility(float direct, vec3 diffuse) const { return visibility<ScalarLanes>(direct, diffuse); }
};

// theta in degrees, g the scene's phase asymmetry, voxel the smallest spacing.
inline ForwardScattering make_forward_scattering(float blend, float cone_angle_deg, float phase_g,
                                                 float scattering_albedo, float voxel) {
  ForwardScattering s;
  s.blend = blend;
  s.scattering_albedo = scattering_albedo;
  const float theta = glm::radians(cone_angle_deg);
  s.cone_fraction = hg_cone_fraction(phase_g, glm::cos(theta));
  const float tan_theta = glm::tan(theta);
  s.spread_per_length = voxel * tan_theta * tan_theta;
  return s;
}

// Visibility a technique has already computed for the sample being shaded,
// handed to ScatteringLighting (lighting.h) as its Visibility: one value per
// lane of the packet being shaded (FixedVisibility: one ray).
template <class L> struct FixedVisibilityL {
  typename L::Vec3 value{1.0f};
  PENUMBRA_HD vec3 operator()(int, vec3, const LightSample&) const
    requires(L::kWidth == 1)
  {
    return value;
  }
  template <class P>
  PENUMBRA_HD typename P::Vec3 lanes(int, const typename P::Vec3&, const LightSampleL<P>&, typename P::Mask) const {
    return value;
  }
};
using FixedVisibility = FixedVisibilityL<ScalarLanes>;

}  // namespace penumbra

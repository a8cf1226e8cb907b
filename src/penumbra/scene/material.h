#pragma once
// How lit samples scatter (DESIGN.md 1). With "phase" shading a sample
// scatters albedo * colour * p(cos) * L * V, where p is the phase function
// scaled so that isotropic p = 1 (see light.h for the matching light units).
// With "phong" shading the gradient Blinn-Phong model replaces p.
#include "penumbra/base/math.h"

namespace penumbra {

enum class Shading : std::uint8_t { Phase, Phong };

struct Material {
  float albedo = 1.0f;   // scattering albedo multiplier (per-channel albedo = albedo * TF colour)
  float phase_g = 0.0f;  // Henyey-Greenstein asymmetry in (-1, 1); 0 = isotropic
  Shading shading = Shading::Phase;
  float ambient = 0.1f;  // unshadowed constant term; not part of the physical model
  float diffuse = 0.9f;
  float specular = 0.2f;
  float shininess = 20.0f;

  // Throws InvalidScene naming "material.<field>" for out-of-range values.
  void validate() const;
};

// Henyey-Greenstein phase function times 4 pi (so isotropic = 1), for one
// cosine or a packet of them (base/lanes.h). cos_theta is
// the cosine of the scattering angle: between the direction the light travels
// and the direction it leaves toward the viewer.
template <class F> PENUMBRA_HD PENUMBRA_FORCE_INLINE F phase_hg_4pi(float g, F cos_theta) {
  const float g2 = g * g;
  const F denom = 1.0f + g2 - 2.0f * g * cos_theta;
  return (1.0f - g2) / (denom * sqrt(denom));
}

}  // namespace penumbra

#pragma once
// Sampling the Henyey-Greenstein phase function (the physical, normalised
// one: phase_hg_4pi / (4 pi)). Its pdf equals the phase function, so a path
// that scatters in the sampled direction carries the albedo as its weight.
#include "penumbra/scene/light_sampling.h"
#include "penumbra/scene/material.h"

namespace penumbra {

// Cosine between the direction a path travels and the one it scatters into,
// distributed as HG with asymmetry g (g > 0: mostly forward). Inverts the
// HG cdf (Pharr, Jakob and Humphreys, "Physically Based Rendering", 3rd ed.,
// eq. 15.7, with cos measured from the travel direction).
PENUMBRA_HD inline float sample_hg_cosine(float g, float u) {
  if (glm::abs(g) < 1e-3f) return 1.0f - 2.0f * u;
  const float s = (1.0f - g * g) / (1.0f - g + 2.0f * g * u);
  return glm::clamp((1.0f + g * g - s * s) / (2.0f * g), -1.0f, 1.0f);
}

// A new travel direction after scattering a path travelling along `direction`.
PENUMBRA_HD inline vec3 sample_hg(vec3 direction, float g, vec2 u) {
  return direction_about(direction, sample_hg_cosine(g, u.x), u.y);
}

}  // namespace penumbra

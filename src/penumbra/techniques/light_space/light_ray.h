#pragma once
// Marching a light ray for map generation, and the transmittance model the
// three shadow maps share.
//
// A light ray is cut into segments with the sampling convention of march.h
// (step = render.step, sample at the segment's midpoint, empty macrocells
// skipped); segment i has optical depth tau_i = sigma_t * length_i,
// opacity alpha_i = 1 - exp(-tau_i) and TF colour t_i. Its transmittance
// per channel lambda, 1 - rho_i,lambda (rho: the probability that a photon
// is stopped), follows one of three colour models (ShadowColorModel):
//
//   grey       rho = alpha: the physical model's transmittance, the one
//              shadow-rays marches.
//   chromatic  (the default of the coloured maps) the extinction is
//              redistributed over the channels by the hue of t:
//                rho_lambda = 1 - exp(-k_lambda tau),
//                k_lambda = 1 + s (mean(c) - c_lambda),  c = t / max(t),
//              s the saturation (0: grey). The k average to 1, so the
//              product of the three channels' transmittances is the grey
//              one cubed: colour tints a shadow without taking its
//              darkness away, and a white or grey TF colour (of any
//              brightness: brightness is what the material reflects)
//              shadows exactly as under shadow-rays.
//   paper      Weidner & Linsen (section 3): a photon interacts with
//              probability alpha and is then transmitted with probability
//              t (the "transport colour"): rho = alpha (1 - t). Bright
//              opaque material lets most light through (a white bone
//              casts no shadow), so it is kept for reproducing the paper.
//
// The light ray's transmittance as a function of depth z is continuous and
// piecewise linear: 1 before the first segment, the product of (1 - rho) of
// the segments that end before z, times 1 - rho_i (z - start_i) / length_i
// inside segment i. Deep shadow maps compress this function and CSSMs
// estimate it without bias (see cssm_kernels.h).
#include "penumbra/render/march.h"

namespace penumbra {

struct LightSegment {
  float start;          // depth where the segment begins
  float length;         // world units
  float alpha;          // opacity of the segment, 1 - exp(-optical_depth)
  vec3 color;           // TF colour of its sample, clamped to [0, 1]
  float optical_depth;  // sigma_t * length
};

enum class ShadowColor : std::uint8_t { Grey, Chromatic, Paper };

struct ShadowColorModel {
  ShadowColor kind = ShadowColor::Chromatic;
  float saturation = 1.0f;  // chromatic only: 0 grey, up to 1.5 (k stays >= 0)
};

// Largest saturation for which every k_lambda of the chromatic model is >= 0
// (c_lambda - mean(c) <= 2/3 when max(c) = 1).
inline constexpr float kMaxShadowSaturation = 1.5f;

// The chromatic model's extinction weights k of a TF colour (they average 1).
PENUMBRA_HD inline vec3 chromatic_extinction_weights(vec3 color, float saturation) {
  const float top = max_component(color);
  if (!(top > 1e-6f)) return vec3(1.0f);  // black: no hue, grey extinction
  const vec3 c = color / top;
  const float mean = (c.r + c.g + c.b) * (1.0f / 3.0f);
  return glm::max(vec3(1.0f) + saturation * (vec3(mean) - c), vec3(0.0f));
}

// Per-channel probability that a photon is not transmitted through the segment.
PENUMBRA_HD inline vec3 stop_probability(const LightSegment& s, const ShadowColorModel& model) {
  switch (model.kind) {
    case ShadowColor::Grey: return vec3(s.alpha);
    case ShadowColor::Paper: return s.alpha * (1.0f - s.color);
    case ShadowColor::Chromatic: break;
  }
  const vec3 k = chromatic_extinction_weights(s.color, model.saturation);
  return vec3(1.0f - exp_nonpositive(-k.r * s.optical_depth), 1.0f - exp_nonpositive(-k.g * s.optical_depth),
              1.0f - exp_nonpositive(-k.b * s.optical_depth));
}

// Calls visit(segment) for every segment with non-zero opacity along `ray`
// within [0, t_max], front to back (from the light). Stops when visit
// returns false. Returns the number of volume samples taken.
template <class Sampler, class Visit>
PENUMBRA_HD std::uint64_t march_light_ray(const RenderView& v, const Sampler& sampler, const Ray& ray, float t_max,
                                          Visit&& visit) {
  const SampleGrid grid(volume_interval(v, ray, 0.0f, t_max), v.step, 0.5f);
  if (grid.count == 0) return 0;
  const vec3 o = v.volume.index_from_world(ray.origin);
  const vec3 d = ray.direction / v.volume.spacing;
  const TransferFunctionView tf = v.tf;
  std::uint64_t samples = 0;
  SampleCursor cursor(v, ray, grid);
  int k;
  float t;
  while (cursor.next(k, t)) {
    ++samples;
    const float value = sampler(o + t * d);
    const vec4 c = Sampler::kAlwaysFinite ? tf.lookup_finite(value) : tf.lookup(value);
    if (c.a <= 0.0f) continue;
    const float length = grid.length(k);
    const float tau = c.a * length;
    const LightSegment segment{grid.start(k), length, 1.0f - exp_nonpositive(-tau),
                               glm::clamp(vec3(c), vec3(0.0f), vec3(1.0f)), tau};
    if (!visit(segment)) break;
  }
  return samples;
}

}  // namespace penumbra

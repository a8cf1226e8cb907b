#pragma once
// Marching a light ray for map generation, and the transmittance model the
// three shadow maps share.
//
// A light ray is cut into segments with the sampling convention of march.h
// (step = render.step, sample at the segment's midpoint, empty macrocells
// skipped); segment i has opacity alpha_i = 1 - exp(-sigma_t * length_i)
// and TF colour t_i. Following Weidner & Linsen (section 3), a photon of
// channel lambda crossing segment i is stopped with probability
//   rho_i,lambda = alpha_i * (1 - t_i,lambda)
// (it interacts with probability alpha_i and is then transmitted with
// probability t_i,lambda, the "transport colour"). Without colour
// (`colored` false) t = 0 and rho_i = alpha_i: the grey transmittance of
// the physical model, the one shadow-rays marches.
//
// The light ray's transmittance as a function of depth z is continuous and
// piecewise linear: 1 before the first segment, the product of (1 - rho) of
// the segments that end before z, times 1 - rho_i (z - start_i) / length_i
// inside segment i. Deep shadow maps compress this function and CSSMs
// estimate it without bias (see cssm_kernels.h).
#include "penumbra/render/march.h"

namespace penumbra {

struct LightSegment {
  float start;   // depth where the segment begins
  float length;  // world units
  float alpha;   // opacity of the segment
  vec3 color;    // TF colour of its sample, clamped to [0, 1]
};

// Per-channel probability that a photon is not transmitted through the segment.
PENUMBRA_HD inline vec3 stop_probability(const LightSegment& s, bool colored) {
  return colored ? s.alpha * (1.0f - s.color) : vec3(s.alpha);
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
    const LightSegment segment{grid.start(k), length, 1.0f - exp_nonpositive(-c.a * length),
                               glm::clamp(vec3(c), vec3(0.0f), vec3(1.0f))};
    if (!visit(segment)) break;
  }
  return samples;
}

}  // namespace penumbra

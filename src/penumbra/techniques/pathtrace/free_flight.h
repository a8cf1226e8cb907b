#pragma once
// Free flights through the heterogeneous medium, unbiased at any step size
// because no step exists: delta tracking (Woodcock et al. 1965) samples the
// distance to the next real collision, ratio tracking (Novak, Selle and
// Jarosz, "Residual Ratio Tracking for Estimating Attenuation in
// Participating Media", SIGGRAPH Asia 2014) estimates the transmittance.
// Both draw tentative collisions against the majorant of the macrocell the
// ray is in (the shared MajorantGrid: a piecewise-constant bound on sigma_t),
// so empty macrocells (majorant 0) are skipped without a single lookup and
// dense cells do not slow down thin ones. sigma_t(x) is the trilinear sample
// looked up in the baked TF table, exactly what every technique marches.
#include "penumbra/base/rng.h"
#include "penumbra/render/march.h"

#include <cstdint>

namespace penumbra {

// A real collision: where, and the medium there.
struct Collision {
  float t = 0.0f;      // ray parameter (world units)
  vec3 color{0.0f};    // TF colour (the scattering albedo before material.albedo)
  float sigma_t = 0.0f;
};

// Exponential step with rate `majorant` (-ln(1 - u) / majorant; u < 1).
PENUMBRA_HD inline float exponential_step(Pcg32& rng, float majorant) {
  return -glm::log(1.0f - rng.next_float()) / majorant;
}

// Delta tracking over [t0, t1] of the ray (the caller clips to the medium:
// volume_interval). Returns true and fills `hit` at the first real collision;
// false when the ray gets through, which happens with probability exp(-tau).
// `lookups` counts volume samples.
template <class Sampler>
PENUMBRA_HD bool delta_tracking(const RenderView& v, const Sampler& sampler, const Ray& ray, float t0, float t1,
                                Pcg32& rng, Collision& hit, std::uint64_t& lookups) {
  if (!(t0 < t1)) return false;
  const vec3 o = v.volume.index_from_world(ray.origin);
  const vec3 d = ray.direction / v.volume.spacing;
  const TransferFunctionView tf = v.tf;
  bool collided = false;
  for_each_occupied_cell(v, ray, t0, t1, [&](float a, float b, float majorant) {
    // Memorylessness of the exponential: restarting at each cell boundary
    // with that cell's majorant is exact.
    float t = a;
    for (;;) {
      t += exponential_step(rng, majorant);
      if (t >= b) return true;
      ++lookups;
      const float value = sampler(o + t * d);
      const vec4 medium = Sampler::kAlwaysFinite ? tf.lookup_finite(value) : tf.lookup(value);
      if (rng.next_float() * majorant < medium.a) {
        hit = Collision{t, vec3(medium), medium.a};
        collided = true;
        return false;
      }
    }
  });
  return collided;
}

// Below this running estimate, ratio tracking plays Russian roulette: the
// ray survives with probability T / threshold and then carries threshold,
// which keeps the estimate unbiased and ends rays deep in shadow early.
inline constexpr float kRatioRouletteThreshold = 0.1f;

// One tentative collision of ratio tracking: the running estimate times the
// null-collision ratio 1 - sigma / majorant, then the roulette; false when
// the estimate is 0 (the ray is done).
PENUMBRA_HD inline bool ratio_tracking_step(float& transmittance, float sigma, float majorant, Pcg32& rng) {
  transmittance *= glm::max(0.0f, 1.0f - sigma / majorant);
  if (transmittance < kRatioRouletteThreshold) {
    if (rng.next_float() * kRatioRouletteThreshold >= transmittance) {
      transmittance = 0.0f;
      return false;
    }
    transmittance = kRatioRouletteThreshold;
  }
  return true;
}

// Ratio-tracking estimate of exp(-integral sigma_t) from ray.origin to t_max
// (a light's distance or +inf), within the volume box and clip planes.
template <class Sampler>
PENUMBRA_HD float ratio_tracking(const RenderView& v, const Sampler& sampler, const Ray& ray, float t_max,
                                 Pcg32& rng, std::uint64_t& lookups) {
  const Interval iv = volume_interval(v, ray, 0.0f, t_max);
  if (iv.empty()) return 1.0f;
  const vec3 o = v.volume.index_from_world(ray.origin);
  const vec3 d = ray.direction / v.volume.spacing;
  const TransferFunctionView tf = v.tf;
  float transmittance = 1.0f;
  for_each_occupied_cell(v, ray, iv.t0, iv.t1, [&](float a, float b, float majorant) {
    float t = a;
    for (;;) {
      t += exponential_step(rng, majorant);
      if (t >= b) return true;
      ++lookups;
      const float value = sampler(o + t * d);
      const float sigma = (Sampler::kAlwaysFinite ? tf.lookup_finite(value) : tf.lookup(value)).a;
      if (!ratio_tracking_step(transmittance, sigma, majorant, rng)) return false;
    }
  });
  return transmittance;
}

}  // namespace penumbra

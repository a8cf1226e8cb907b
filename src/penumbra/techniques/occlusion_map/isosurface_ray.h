#pragma once
// Isosurface ray casting (Penner & Mitchell 2008, section 4.3): march to the
// first sample at or above the iso-value, then refine the crossing by binary
// search between it and the sample before. The view must be an IsoOccupancy
// view, so that cells entirely below the iso-value are skipped and a skipped
// sample is known to lie below it.
#include "penumbra/render/march.h"

#include <cstdint>

namespace penumbra {

// Bisections after the bracketing step: the bracket shrinks to step / 2^12,
// about 1e-4 voxel at the default half-voxel step.
inline constexpr int kIsoBisections = 12;

// Ray parameter of the first crossing of `iso` within `interval`, or
// kInfinity. A ray that starts inside (value >= iso at interval.t0, e.g. at a
// clip plane) hits at interval.t0. Counts the samples it takes.
template <class Sampler>
PENUMBRA_HD float first_iso_crossing(const RenderView& v, const Sampler& sampler, const Ray& ray, Interval interval,
                                     float iso, std::uint64_t& samples) {
  // Samples at segment ends (offset 1), so the brackets cover [t0, t1] whole.
  const SampleGrid grid(interval, v.step, 1.0f);
  if (grid.count == 0) return kInfinity;
  const vec3 o = v.volume.index_from_world(ray.origin);
  const vec3 d = ray.direction / v.volume.spacing;
  SampleCursor cursor(v, ray, grid);
  int k;
  float t;
  while (cursor.next(k, t)) {
    ++samples;
    float hi_value = sampler(o + t * d);
    if (!(hi_value >= iso)) continue;
    // The bracket's lower end: the previous sample (below the iso-value,
    // sampled or skipped as empty) or the interval start, where the ray may
    // already be inside (or a cell border rounded the skip).
    float lo = k == 0 ? interval.t0 : grid.position(k - 1);
    float lo_value = sampler(o + lo * d);
    ++samples;
    if (lo_value >= iso) return lo;
    float hi = t;
    for (int i = 0; i < kIsoBisections; ++i) {
      const float mid = 0.5f * (lo + hi);
      const float value = sampler(o + mid * d);
      if (value >= iso) {
        hi = mid;
        hi_value = value;
      } else {
        lo = mid;
        lo_value = value;
      }
    }
    samples += kIsoBisections;
    // A last secant step inside the final bracket.
    const float span = hi_value - lo_value;
    return span > 0.0f ? lo + (hi - lo) * glm::clamp((iso - lo_value) / span, 0.0f, 1.0f) : hi;
  }
  return kInfinity;
}

// Hard shadows: true when the segment [0, t_max] of the ray, clipped to the
// volume and the clip planes, reaches the iso-value anywhere.
template <class Sampler>
PENUMBRA_HD bool iso_blocks(const RenderView& v, const Sampler& sampler, const Ray& ray, float t_max, float iso) {
  const SampleGrid grid(volume_interval(v, ray, 0.0f, t_max), v.step, 1.0f);
  if (grid.count == 0) return false;
  const vec3 o = v.volume.index_from_world(ray.origin);
  const vec3 d = ray.direction / v.volume.spacing;
  SampleCursor cursor(v, ray, grid);
  int k;
  float t;
  while (cursor.next(k, t)) {
    if (sampler(o + t * d) >= iso) return true;
  }
  return false;
}

}  // namespace penumbra

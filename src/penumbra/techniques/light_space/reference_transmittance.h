#pragma once
// For tests: the transmittance of light_ray.h computed by brute force, i.e.
// every segment of the light ray sampled (no empty-space skipping, no early
// stop), with the untyped VolumeView sampler, so that the maps' fast paths
// are checked against an independent loop. The colour models are written
// out again here from their definition in light_ray.h.
#include "penumbra/render/march.h"
#include "penumbra/techniques/light_space/light_ray.h"

#include <algorithm>
#include <cmath>

namespace penumbra {

// Per-channel transmittance of one segment of optical depth tau, opacity
// alpha and TF colour t (clamped) under `model`.
inline vec3 reference_segment_transmittance(float tau, vec3 t, const ShadowColorModel& model) {
  const float alpha = 1.0f - std::exp(-tau);
  if (model.kind == ShadowColor::Grey) return vec3(1.0f - alpha);
  if (model.kind == ShadowColor::Paper) return 1.0f - alpha * (1.0f - t);
  const float top = std::max(t.r, std::max(t.g, t.b));
  vec3 k(1.0f);
  if (top > 1e-6f) {
    const vec3 c = t / top;
    const float mean = (c.r + c.g + c.b) / 3.0f;
    for (int i = 0; i < 3; ++i) k[i] = std::max(0.0f, 1.0f + model.saturation * (mean - c[i]));
  }
  return vec3(std::exp(-k.r * tau), std::exp(-k.g * tau), std::exp(-k.b * tau));
}

// Per-channel transmittance along `ray` from its volume entry to depth z.
inline vec3 reference_transmittance(const RenderView& v, const Ray& ray, float z, const ShadowColorModel& model) {
  const SampleGrid grid(volume_interval(v, ray, 0.0f, kInfinity), v.step, 0.5f);
  vec3 transmittance(1.0f);
  for (int k = 0; k < grid.count && grid.start(k) < z; ++k) {
    const vec4 c = v.tf.lookup(v.volume.sample(ray.at(grid.position(k))));
    const float length = grid.length(k);
    const vec3 stop =
        1.0f - reference_segment_transmittance(c.a * length, glm::clamp(vec3(c), vec3(0.0f), vec3(1.0f)), model);
    const float inside = std::min(1.0f, (z - grid.start(k)) / length);
    transmittance *= 1.0f - stop * inside;
  }
  return transmittance;
}

// The depth where `ray` enters the occluder: where its least channel's
// transmittance (piecewise linear, as above) falls to 1 - opacity; +inf
// when it never does.
inline float reference_entry(const RenderView& v, const Ray& ray, const ShadowColorModel& model, float opacity) {
  const SampleGrid grid(volume_interval(v, ray, 0.0f, kInfinity), v.step, 0.5f);
  float transmittance = 1.0f;
  for (int k = 0; k < grid.count; ++k) {
    const vec4 c = v.tf.lookup(v.volume.sample(ray.at(grid.position(k))));
    const float length = grid.length(k);
    const vec3 t = reference_segment_transmittance(c.a * length, glm::clamp(vec3(c), vec3(0.0f), vec3(1.0f)), model);
    const float after = transmittance * std::min(t.r, std::min(t.g, t.b));
    if (after <= 1.0f - opacity) {
      return grid.start(k) + (transmittance - (1.0f - opacity)) / (transmittance - after) * length;
    }
    transmittance = after;
  }
  return kInfinity;
}

}  // namespace penumbra

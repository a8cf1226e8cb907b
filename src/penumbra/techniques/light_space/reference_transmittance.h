#pragma once
// For tests: the transmittance of light_ray.h computed by brute force, i.e.
// every segment of the light ray sampled (no empty-space skipping, no early
// stop), with the untyped VolumeView sampler, so that the maps' fast paths
// are checked against an independent loop.
#include "penumbra/render/march.h"

#include <algorithm>
#include <cmath>

namespace penumbra {

// Per-channel transmittance along `ray` from its volume entry to depth z.
inline vec3 reference_transmittance(const RenderView& v, const Ray& ray, float z, bool colored) {
  const SampleGrid grid(volume_interval(v, ray, 0.0f, kInfinity), v.step, 0.5f);
  vec3 transmittance(1.0f);
  for (int k = 0; k < grid.count && grid.start(k) < z; ++k) {
    const vec4 c = v.tf.lookup(v.volume.sample(ray.at(grid.position(k))));
    const float length = grid.length(k);
    const float alpha = 1.0f - std::exp(-c.a * length);
    const vec3 t = colored ? glm::clamp(vec3(c), vec3(0.0f), vec3(1.0f)) : vec3(0.0f);
    const vec3 stop = alpha * (1.0f - t);
    const float inside = std::min(1.0f, (z - grid.start(k)) / length);
    transmittance *= 1.0f - stop * inside;
  }
  return transmittance;
}

}  // namespace penumbra

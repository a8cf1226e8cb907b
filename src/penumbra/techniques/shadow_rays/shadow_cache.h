#pragma once
// Shadow cache: a float grid over the volume's world box holding, per texel,
// the transmittance toward one light; sampled trilinearly.
#include "penumbra/render/march.h"
#include "penumbra/scene/light.h"
#include "penumbra/volume/volume.h"

namespace penumbra {

// Transmittance toward `light` from a world position, by shadow-ray marching.
PENUMBRA_HD inline float light_transmittance(const RenderView& v, vec3 p, const Light& light, float density_scale,
                                             RayStats& stats) {
  const LightSample ls = sample_light(light, p);
  return march_transmittance(v, Ray{p, ls.to_light}, ls.distance, density_scale, stats);
}

// Builds one cache texel grid per light; `resolution` scales the data dims.
Volume build_shadow_cache(const RenderView& v, const Light& light, float density_scale, float resolution);

}  // namespace penumbra

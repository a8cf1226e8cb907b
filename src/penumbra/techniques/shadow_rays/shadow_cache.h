#pragma once
// Shadow cache: a float grid over the volume's world box holding, per texel,
// the transmittance toward one light; sampled trilinearly.
#include "penumbra/render/march.h"
#include "penumbra/scene/light.h"
#include "penumbra/techniques/shadow_rays/area_light_transmittance.h"
#include "penumbra/volume/volume.h"

namespace penumbra {

// Transmittance toward light `light_index` of the view from a world position,
// by shadow-ray marching: one ray toward its centre, or with
// light_samples > 1 and a light with an extent the area mean of
// area_light_transmittance.h (the same rays the uncached path marches).
PENUMBRA_HD inline float light_transmittance(const RenderView& v, vec3 p, int light_index, float density_scale,
                                             int light_samples, RayStats& stats) {
  const Light& light = v.lights[light_index];
  if (light_samples > 1 && light_has_extent(light)) {
    const AnyVoxelSampler sampler(v.volume.data, v.volume.dims, v.volume.type);
    return area_light_transmittance<ScalarLanes>(v, sampler, light, light_index, &p, light_samples, density_scale,
                                                 true, stats);
  }
  const LightSample ls = sample_light(light, p);
  return march_transmittance(v, Ray{p, ls.to_light}, ls.distance, density_scale, stats);
}

// Builds the cache texel grid of light `light_index`; `resolution` scales the
// data dims.
Volume build_shadow_cache(const RenderView& v, int light_index, float density_scale, int light_samples,
                          float resolution);

}  // namespace penumbra

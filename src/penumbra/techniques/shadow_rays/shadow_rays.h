#pragma once
// shadow-rays: single scattering with exact light visibility (DESIGN.md 1),
// the hard-shadow reference every soft-shadow technique is compared with.
// V_light(x) is the transmittance exp(-integral sigma_t) marched from x to
// the volume boundary (directional) or to the light (point), with the same
// step, clip planes and empty-space skipping as the viewing rays.
//
// Parameters
//   shadow_density_scale  multiplies sigma_t along shadow rays only (0 = no
//                         shadows, i.e. unshadowed single scattering)
//   shadow_cache          precompute V per light on a grid (Ament et al. 2014,
//                         Algorithm 1, used with exact transmittance) and
//                         interpolate it instead of marching per sample
//   cache_resolution      cache grid size as a fraction of the data grid
// Passes
//   prepare: with the cache on, one transmittance volume per light, rebuilt
//            only when the data, TF, lights, clip planes or these parameters
//            change
//   render:  one ray-casting pass; per lit sample one shadow ray per light
//            (or one cache lookup)
#include "penumbra/render/technique.h"

namespace penumbra {

TechniqueInfo shadow_rays_info();

}  // namespace penumbra

#pragma once
// sat-ao: extinction-based ambient occlusion from a volume-aligned summed-area
// table (P. Schlegel, M. Makhinya, R. Pajarola, "Extinction-based shading and
// illumination in GPU volume ray-casting", IEEE TVCG 17(12), 2011), the AO
// baseline of Ament et al. 2014 (Table 1, "AO"). The mean extinction in the
// cube of half-width R around a sample, from 8 table reads, gives the
// transmittance exp(-sigma_mean R) that a homogeneous medium of that
// extinction has over the radius: the occlusion of light arriving from the
// sample's neighbourhood, without a direction. It is each light's visibility
// (the shared lighting keeps `ambient` unoccluded).
//
// Parameters
//   radius_voxels         R, the occlusion radius in voxels
//   sat_resolution        table cells per voxel along each axis
//   shadow_cache          store the occlusion on a grid instead of reading
//                         the table per sample
//   cache_resolution      that grid's size as a fraction of the data grid
//   shadow_density_scale  multiplies the mean extinction
// Passes
//   prepare: the table when the data, the shadow TF's extinction, the clip
//            planes or the resolution change (never for lights, floor planes
//            or a render-only TF edit); with the cache, one occlusion grid, also
//            rebuilt when the radius, density scale or cache resolution change
//   render:  one ray-casting pass; per lit sample one cache read (or one
//            box sum), shared by every light
#include "penumbra/render/technique.h"

namespace penumbra {

TechniqueInfo sat_ao_info();

}  // namespace penumbra

#pragma once
// cone-shadows: soft shadows from a cone toward each light, approximated by a
// series of growing cubes read from a volume-aligned summed-area table
// (P. Schlegel, M. Makhinya, R. Pajarola, "Extinction-based shading and
// illumination in GPU volume ray-casting", IEEE TVCG 17(12), 2011), the "CS"
// baseline of Ament et al. 2014 (section 6, Fig. 8, Table 1). The cone is
// marched in steps; each step's cube, centred on the cone axis, has the
// cone's half-width there (at least half a step, so consecutive cubes
// touch), and its mean extinction times the step length adds to the optical
// depth. Unlike filtered-sat the cost grows with the distance to the light
// over the step, and the cubes stay aligned with the data axes whatever the
// light direction.
//
// Parameters
//   cone_angle_deg        half-angle of the cone
//   step_voxels           length of a cone step in voxels
//   sat_resolution        table cells per voxel along each axis
//   shadow_cache          store each light's transmittance on a grid
//   cache_resolution      that grid's size as a fraction of the data grid
//   shadow_density_scale  multiplies the optical depth
// Passes
//   prepare: the table when the data, the shadow TF's extinction, the clip
//            planes or the resolution change (not for floor planes, lights
//            or a render-only TF edit); with the cache, one transmittance
//            grid per light, rebuilt with the table, for that light when it
//            moves (not for its colour or intensity), and for all when the
//            cone parameters change
//   render:  one ray-casting pass; per lit sample one cache read per light
//            (or one cone march)
#include "penumbra/render/technique.h"

namespace penumbra {

TechniqueInfo cone_shadows_info();

}  // namespace penumbra

#pragma once
// ambient-scattering: soft shadows along a tube of spheres with preintegrated
// scattering over a volume-aligned SAT (M. Ament, F. Sadlo, D. Weiskopf,
// "Ambient volume scattering", IEEE TVCG 19(12), 2013), the "AS" baseline of
// Ament et al. 2014 (section 6, Fig. 8c/f, Table 1). Our reconstruction from
// the 2014 paper's account of it and the 2013 abstract (the 2013 paper's
// text was not available; docs/filtered-sat.md, "The AS baseline", says what
// is the paper's and what is ours):
//
// - Ambient sphere: a sample x sees its neighbourhood, a sphere of radius R
//   (the ambient radius), as a homogeneous medium of the sphere's mean
//   extinction (read from the SAT over its bounding cube, as sat-ao's),
//   optical radius tau = sigma_mean R.
// - Preintegration: for such a ball of albedo a (scattering_albedo, one grey
//   value as in the paper's tables) and the material's Henyey-Greenstein g,
//   lit by a unit beam, the light scattered inside it at all orders is
//   integrated once (scattering_table.h), independent of data and TF.
// - Tube: toward each light, spheres of radius R at 2R, 4R, ... (the paper:
//   "a radius of 8 voxels leads to a step size of 16 voxels"); each passes
//   on F(tau_k), its forward transmission including forward scattering, so
//   the light reaching x's sphere is the product of the F(tau_k).
// - View-dependent lookup: x's own sphere scatters M(tau_0, mu) of that
//   toward the viewer (mu = cos of light vs view), relative to the
//   single-scattering phase function the shared lighting applies, so the
//   visibility is prod_k F(tau_k) * M(tau_0, mu). It may exceed 1 where
//   multiple scattering outshines the phase function's own lobe (backward
//   directions under a forward g). With a = 0 it is exp(-R sigma_0 - 2R
//   sum_k sigma_k), a soft (tube-averaged) shadow ray.
//
// Parameters
//   radius_voxels         R in voxels (< 0: from the lights' sizes, as the
//                         filter of filtered-sat: half the box width of the
//                         widest derived filter over the cube factor; 8,
//                         the paper's Fig. 8c, for directional and point lights)
//   scattering_albedo     a of the preintegrated scattering (0.6: the
//                         paper's best match to the other methods, Fig. 8)
//   preintegration_paths  Monte Carlo paths per table node
//   sat_resolution        table cells per voxel (0.5: the paper's comparisons)
//   shadow_cache          store each light's tube transfer (and one grid of
//                         the own spheres' optical radii) on a grid
//   cache_resolution      that grid's size as a fraction of the data grid
//   shadow_density_scale  multiplies the spheres' extinction
// Passes
//   prepare: the scattering table when a, g or the paths change (shared by
//            the process); the SAT when the data, the shadow TF's
//            extinction, the clip planes or the resolution change (not for
//            floor planes, lights or a render-only TF edit); with the cache,
//            the optical-radius grid with the table or when R, the density
//            scale or the cache resolution change, and one tube grid per
//            light, rebuilt for that light when it moves (not for its colour
//            or intensity), and for all with the table; per light and opaque
//            plane a 2D grid of the surface visibility (plane_caches.h)
//   render:  one ray-casting pass; per lit sample two cache reads and one
//            view-dependent table read per light (or a tube march of 2R
//            steps), per plane pixel one bilinear read
#include "penumbra/render/technique.h"

namespace penumbra {

TechniqueInfo ambient_scattering_info();

}  // namespace penumbra

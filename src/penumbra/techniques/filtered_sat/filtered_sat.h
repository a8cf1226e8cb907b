#pragma once
// filtered-sat: low-pass filtered volumetric shadows (M. Ament, F. Sadlo,
// C. Dachsbacher, D. Weiskopf, "Low-Pass Filtered Volumetric Shadows", IEEE
// TVCG 20(12), 2014). Single scattering in which the optical depth toward a
// light is replaced by its mean over a patch facing the light (eq. 4), read
// from summed-area tables aligned with the lights, so the cost of a shadow
// does not depend on its softness and no shadow ray is marched:
//   directional lights: a CSAT whose w axis points at the light; one table
//     serves up to six orthodirectional lights (4.2.1, 4.2.2)
//   point lights: a spherical SSAT about the light (4.2.3), inside or
//     outside the volume
//   box filter in constant time, Gaussian from sub-cuboids (4.3)
//
// Parameters
//   filter_voxels         patch width in voxels of the smallest spacing (the
//                         Gaussian gets the same variance as this box)
//   kernel                box | gaussian
//   patch_offset          start the filtered volume this many filter
//                         half-widths toward the light (0: the paper's cuboid
//                         from the sample; more leaves out the material of
//                         the lit surface a sample lies on)
//   sat_resolution        table cells per voxel along each axis (1 = the data
//                         resolution; the paper's comparisons use 0.5)
//   shadow_cache          store each light's transmittance on a grid
//                         (Algorithm 1) instead of reading the tables per sample
//   cache_resolution      that grid's size as a fraction of the data grid
//   cache_tolerance       cache cells whose 8 texels differ by more than this
//                         read the tables instead (1: the cache everywhere)
//   shadow_density_scale  multiplies the filtered optical depth (Fig. 7b)
// Passes
//   prepare: the tables, each rebuilt when what it is made of changes: the
//            data (or time step), the shadow TF's extinction, the clip
//            planes, sat_resolution, or its own light's direction or
//            position (never for a colour, an intensity, a floor plane or a
//            render-only TF edit); then, with the cache, one transmittance
//            grid per light, rebuilt when its table is, or when the filter,
//            kernel, offset, density scale or cache resolution change.
//            Tables are float residuals against double block corners
//            (summed_area_table.h). When the render reads no table (the
//            cache on, cache_tolerance 1, no floor plane), each light's
//            table is built just before its cache and released after it
//            (the paper's section 7), so memory holds the caches and at
//            most one table; a light that moves gets its table rebuilt then
//   render:  one ray-casting pass; per lit sample one cache read per light,
//            or one table lookup (4 column sums for the box, 81 for the
//            Gaussian) where the cache cell is not smooth; points outside
//            the volume box (floors) always read the tables
#include "penumbra/render/technique.h"

namespace penumbra {

TechniqueInfo filtered_sat_info();

}  // namespace penumbra

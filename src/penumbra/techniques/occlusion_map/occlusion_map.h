#pragma once
// occlusion-map: isosurface rendering with ambient occlusion and soft shadows
// from filterable occlusion maps (E. Penner, R. Mitchell, "Isosurface Ambient
// Occlusion and Soft Shadows with Filterable Occlusion Maps", IEEE/EG Volume
// Graphics 2008). A pyramid of Gaussian-filtered moment volumes of the data
// (moment_pyramid.h) gives, for any region and any query value, a bound on
// the fraction of voxels above that value (moment_bounds.h), i.e. the
// fraction of the region inside the surface. Because the map depends on the
// data only, the iso-value and the TF change without rebuilding it (the
// iso-value does rebuild the soft-shadow grids below, which march for it).
//
// Parameters
//   iso_value          the iso-value, normalised to the TF range (0 = range
//                      min, 1 = range max; the range is the data range unless
//                      the TF names one), in [0, 1]
//   mode               iso: isosurface ray casting; dvr: the scene's DVR with
//                      the same ambient occlusion (Fig. 11) and soft shadows
//                      read from a grid per light
//   dvr_ao             mode dvr: grid (the AO evaluated once per voxel into a
//                      16-bit grid, read trilinearly per sample) or sample
//                      (evaluated per DVR sample, the paper's Fig. 11)
//   shadows            none | hard (a ray with the iso test; mode iso only) |
//                      soft (a march through the occlusion map accumulating
//                      transmittance, occluders at any value above the
//                      iso-value; in mode dvr marched once per grid node)
//   ambient_occlusion  on/off
//   ao_combine         max (the paper) | mean of the four levels' occlusion |
//                      product of their unoccluded fractions (default: the
//                      closest to brute-force AO, docs/PERFORMANCE.md, issue
//                      17 section)
//   ao_offset          distance of each level's AO sample from the surface,
//                      in that level's Gaussian sigmas
//   ao_lights          AO also darkens the lights (the paper's figures), not
//                      only the ambient term
//   light_size_deg     angular radius of the lights for soft shadows. Unset
//                      (< 0, the default): each light's own size
//                      (occlusion_queries.h light_spread: a distant light's
//                      tan(angle_deg), the RMS of both spreads for an
//                      anisotropic Gaussian; a sphere's or disk's
//                      r / sqrt(d^2 - r^2) from the shaded point at distance
//                      d, so the cone just contains the sphere) and 3 degrees
//                      for directional and point lights. Set (>= 0): that
//                      radius for every light, overriding their sizes
//   moments            2 (Chebyshev, the paper) or 4 (Hamburger bound)
//   resolution         level 0 grid as a fraction of the data grid
//   kernel_size        taps of level 0's Gaussian at level-0 resolution (odd)
// Passes
//   prepare: the moment pyramid, only when the data, the clip planes or the
//            three map parameters (moments, resolution, kernel_size) change (rebuilds()
//            counts these builds); a per-macrocell iso flag grid when the
//            iso-value changes (a few thousand comparisons); mode dvr with
//            soft shadows: per light a grid over the volume's box at the
//            map's level-0 resolution, one soft-shadow march per node (SIMD
//            packets for two moments), rebuilt when the light moves or
//            changes size, the iso-value, the pyramid or light_size_deg /
//            ao_offset change, kept for TF and camera changes (counted in
//            rebuilds()); mode dvr with dvr_ao=grid: the AO grid, one node
//            per voxel, rebuilt with the pyramid, ao_offset or ao_combine,
//            kept for iso-value, TF, light and camera changes (counted);
//            soft shadows and opaque planes (both modes): per light and
//            plane a 2D grid of the soft shadow over the plane's region the
//            volume can shadow (sat_common/plane_caches.h), one node per
//            voxel, rebuilt when a light or plane moves or when what the
//            march reads changes (not counted in rebuilds())
//   render:  iso: one ray per pixel to the first crossing, refined by binary
//            search, shaded Blinn-Phong with the central-difference gradient;
//            AO from four pyramid lookups along the normal; per light a hard
//            shadow ray or a soft-shadow march. dvr: the shared compositing
//            loop with the AO per sample (one trilinear read of the AO grid,
//            or four pyramid lookups) and one trilinear read of each light's
//            grid, as CPU packets for two moments (one lane at a time for
//            four); planes as in iso mode. A plane point's soft shadow is a
//            bilinear read of its grid where it has one.
// Outside the volume's box nothing occludes: a region reaching past the box
// counts only its inside share (occlusion_queries.h).
// Clip planes cut the surface, the hard-shadow rays and the map: clipped
// voxels enter the moments as air, so clipped material occludes nothing (a
// change of clip planes rebuilds the pyramid).
#include "penumbra/render/technique.h"

namespace penumbra {

TechniqueInfo occlusion_map_info();

}  // namespace penumbra

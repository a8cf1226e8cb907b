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
// The filter from the light's size (filter_voxels unset, < 0, the default;
// issue 18). The paper's filter has one width for the whole volume, while a
// light of angular radius theta softens a shadow cast from distance s by a
// disk of radius s tan(theta), different for every occluder-receiver pair.
// So the width is the light's at one representative occluder distance D:
//   D = a third of the volume box's chord through its centre toward the
//       light: the mean distance between two points spread uniformly along
//       that chord, i.e. between a receiver and an occluder on one light ray
//       through the volume (shadow_filter.h)
//   distant, uniform   the disk of radius R = D tan(theta) (theta =
//                      angle_deg, the cone's half-angle), as the box of the
//                      same per-axis variance (R^2 / 4 = w^2 / 12): w = sqrt(3) R
//   distant, gaussian  per-axis spread D tan(sigma) (the RMS of angle_deg and
//                      angle_y_deg for an anisotropic light, which a square
//                      patch cannot follow): w = sqrt(12) D tan(sigma), with
//                      the Gaussian kernel (kernel = auto)
//   sphere, disk       radius r at distance L from the box centre, occluders
//                      at D' = min(D, L / 2): by similar triangles the disk of
//                      radius R = r D' / (L - D') (a disk as if seen face
//                      on), w = sqrt(3) R
//   directional, point 5 voxels (the former default)
// Widths are clamped to filter_voxels' range. The first 8 lights get their
// own filters, further ones 5 voxels; an explicit filter_voxels applies to
// every light (with the box kernel under kernel = auto). Consequences of the
// constant width, measured in filtered_sat_light_test.cpp: a shadow's
// softness does not grow with the distance to its occluder, so it is the
// light's only at distance D (sharper below, softer above); and the paper's
// model takes exp of the filtered optical depth, so under an optically thick
// edge the 10-90 % penumbra is ln(9) / tau of the filter width (tau the
// occluder's optical depth), narrower than the light's.
//
// Parameters
//   filter_voxels         patch width in voxels of the smallest spacing (the
//                         Gaussian gets the same variance as this box);
//                         < 0: from each light's size (above)
//   kernel                auto (box; gaussian for a derived gaussian light's
//                         filter) | box | gaussian
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
//                         are rough: they read their bricks (1: the cache
//                         everywhere, 0: the tables in every cell that varies)
//   cache_refinement      texels per cell edge of the finest bricks; a rough
//                         cell gets the coarsest of 2, 4, ... up to this whose
//                         read meets the probe tolerance (0: the tables there
//                         instead, which then stay; 1 refused)
//   table_streaming       auto | on | off: when tables are released, a light's
//                         cache, bricks and grids from a stream of its
//                         table's layers instead of the table
//                         (streamed_table.h); auto streams tables over 512 MiB
//   shadow_density_scale  multiplies the filtered optical depth (Fig. 7b)
// Passes
//   prepare: the tables, each rebuilt when what it is made of changes: the
//            data (or time step), the shadow TF's extinction, the clip
//            planes, sat_resolution, or its own light's direction or
//            position (never for a colour, an intensity or a render-only TF
//            edit); then, with the cache, one 16-bit transmittance grid per light,
//            rebuilt when its table is, or when the filter, kernel, offset,
//            density scale or cache settings change (a light's size changes
//            only its own derived filter and cache). With each light's
//            cache, while its table lives: bricks of its rough cells
//            (sat_common/refined_cells.h: n^3 8-bit codes of the optical
//            depth, n from 2 to cache_refinement as the cell needs, for the
//            cells whose trilinear read misses the cube root of the
//            visibility by more than 0.007 at a probe) and a grid on each opaque plane
//            (sat_common/plane_caches.h over the box grown by the patch's
//            reach, nodes a fifth of the filter apart within 0.25-1 voxel).
//            Tables are float residuals against double block corners
//            (summed_area_table.h). When the render reads no table (the
//            cache on, bricks or cache_tolerance 1, a grid for every light
//            on every plane: the defaults, unless a light grazes a plane),
//            each light's table is built just before its cache and released
//            after its bricks and plane grids (the paper's section 7), so
//            memory holds the caches, bricks and grids and at most one
//            table; a light that moves, a filter change or a plane move
//            (for the grids) then rebuild the tables, one at a time. A
//            streamed light (table_streaming) holds no table: each batch of
//            its points (cache texels, brick probes, brick texels, grid
//            nodes) is sorted by its depth along the light and evaluated
//            while two node layers of the table, summed from the light's
//            face, stream past
//   render:  one ray-casting pass; per lit sample one cache read per light,
//            a brick read in rough cells (or one table lookup without
//            bricks: 4 column sums for the box, 81 for the Gaussian); plane
//            hits read the light's grid on that plane (the tables without)
#include "penumbra/render/technique.h"

namespace penumbra {

TechniqueInfo filtered_sat_info();

}  // namespace penumbra

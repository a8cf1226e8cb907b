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
// The cone from the light's size (cone_angle_deg unset, < 0, the default):
// the cone is the paper's model of the light's solid angle seen from the
// shaded point, so
//   distant, uniform   half-angle = angle_deg (light.h: the cone's half-angle)
//   distant, gaussian  the uniform cone with the same variance on the virtual
//                      light plane: a disk of radius R has per-axis variance
//                      R^2 / 4, so tan(half-angle) = 2 tan(sigma) (sigma the
//                      RMS of angle_deg and angle_y_deg for an anisotropic
//                      one, whose anisotropy a circular cone cannot follow)
//   sphere, disk       the half-angle the radius subtends from the shaded
//                      point at distance d from the centre:
//                      tan = r / sqrt(d^2 - r^2) (a disk as if seen face on)
//   directional, point 5 degrees (the former default)
// The first 8 lights get derived cones; further ones take 5 degrees. An
// explicit cone_angle_deg >= 0 applies to every light, overriding the above.
// Under an opaque edge the paper's model gives a narrower penumbra than the
// light's (exp of the mean extinction over the cube, not the mean
// visibility), so equal angles are equal light sizes, not equal penumbrae:
// measured 0.64 of the light's 10-90 % width at 6 degrees, 0.61 at 12
// (cone_shadows_test.cpp, EdgePenumbraScalesWithTheLightsAngle).
//
// Parameters
//   cone_angle_deg        half-angle of the cone (< 0: from each light)
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
//            and, with the cache, a 2D grid per light on each opaque plane
//            (sat_common/plane_caches.h: one node per voxel over the region
//            the box can shadow), rebuilt with the 3D caches and when a plane
//            moves (which rebuilds() does not count)
//   render:  one ray-casting pass; per lit sample one cache read per light
//            (or one cone march), per plane pixel one bilinear read
#include "penumbra/render/technique.h"

namespace penumbra {

TechniqueInfo cone_shadows_info();

}  // namespace penumbra

#pragma once
// half-angle: half-angle slicing, J. Kniss, S. Premoze, C. Hansen and D. Ebert,
// "Interactive Translucent Volume Rendering and Procedural Modeling", IEEE
// Visualization 2002, and J. Kniss et al., "A Model for Volume Lighting and
// Modeling", IEEE TVCG 9(2), 2003: the slice-based baseline IPSVI (Sundén et
// al. 2011) is compared with. The volume is sliced perpendicular to the
// vector halfway between the view and light directions (flipped for a light
// facing the viewer), so one pass over the slices composites the eye buffer
// and carries the light buffer along; the light buffer is attenuated by each
// slice and its forward-scattered part blurred within a cone (directional
// diffusion). Same optical model as ipsvi (ipsvi/forward_scattering.h), so at
// albedo 0 it is single scattering with hard shadows, like shadow-rays.
//
// Parameters
//   slices          slices through the box (0: one per ray step along the
//                   central viewing ray, like a ray caster)
//   cone_angle_deg  half-angle theta of the forward-scattering cone
//   albedo          blend of forward multiple scattering (0: single scattering)
//   light_buffer_size  light buffer texels per side (0: the image's larger
//                   side, as Kniss et al. match the eye buffer, or ipsvi's
//                   texel per pixel at the volume where that is finer, as
//                   when the camera zooms in)
// Passes
//   prepare: checks light_buffer_size; per light, the light buffer's
//            projection over the box and each texel's light ray (rebuilt
//            when the lights, the data or the buffer size change, not for a
//            camera move or a TF change: the slicing axis, which follows the
//            camera, enters as two dot products per texel and slice)
//   render:  per light, one sweep over the slices (half_angle_renderer.h);
//            the diffuse blur covers every texel the light has reached
//
// A CPU implementation of a GPU method: the "textured slices" are the slice
// planes sampled where each viewing ray (eye buffer) and each light-buffer
// texel's light ray crosses them. Limits inherited from the method: a point
// light whose rays run against the slicing order (a light inside or beside the
// volume) leaves those rays unattenuated, and with extreme fields of view a
// viewing ray crossing the slices against the compositing order is skipped.
#include "penumbra/render/technique.h"

namespace penumbra {

TechniqueInfo half_angle_info();

}  // namespace penumbra

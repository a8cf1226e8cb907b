#pragma once
// ipsvi: image plane sweep volume illumination, E. Sundén, A. Ynnerman and
// T. Ropinski, "Image Plane Sweep Volume Illumination", IEEE TVCG 17(12),
// 2011 (shared/papers/sunden2011-image-plane-sweep-volume-illumination.txt).
// Shadows and forward scattering computed inside the ray caster: the image is
// swept line by line away from the light, and a 2D illumination cache in light
// space carries the light that has reached the current sweep plane, so the
// extra memory is one light-space image, whatever the data size.
//
// Parameters
//   albedo                 the paper's a(s) (eq. 2): blend of single scattering
//                          (0: exactly shadow-rays' model) and forward multiple
//                          scattering within the cone (forward_scattering.h)
//   cone_angle_deg         half-angle theta of that cone
//   line_width             image lines per synchronised block (4.2, 5.2)
//   cache_size             illumination cache texels per side (4.3, 5.2); 0: a
//                          texel about a pixel wide at the visible part of the
//                          volume, at most three times the image's longer
//                          side
//                          (Fig. 9: the size matters; texels finer than the
//                          rays of a line leave holes that cost longer light
//                          segments). Either way the cache spans only what the
//                          camera sees (cache_fit.h)
//   piecewise_integration  march the light segment back to the previous cache
//                          plane (4.4) instead of compositing one step
//   early_termination      the ERT extension of 5.1
//   light_model            grey (the default: shadow-rays' grey
//                          transmittance, one global albedo) or paper (Eq. 3's
//                          light coloured by the medium it crosses, a(s) per
//                          sample, the cone-mean phase): light_model.h
// Passes
//   prepare: per light, the cache projection fitted to the camera frustum's
//            intersection with the volume box (5.2, cache_fit.h) and the
//            cache's starting state: refitted when the camera moves (ray-box
//            tests per texel, no volume samples), rebuilt when lights, data,
//            clip planes or cache_size change; never for a TF change
//   render:  per light, [ERT pre-pass and sweep toward the light,] then the
//            sweep of sweep_plan.h; rays of a block of lines in parallel,
//            each marching the volume with the cache (ipsvi_ray.h)
//
// Special cases (4.4), as handled here:
//   - light along the view direction: with a perspective camera s'_l is the
//     image centre and the four-zone sweep applies; with an orthographic camera
//     the light's image direction is undefined and the previous frame's line
//     direction is kept (the paper's suggestion); every light ray is then one
//     viewing ray and the in-ray propagation of ipsvi_ray.h carries the light.
//   - point light in front of, behind or inside the volume: each ray is
//     traversed away from the light (ipsvi_ray.h); with the light behind the
//     camera plane the sweep runs inward, from the image border toward s'_l.
//   - volume partly off screen: only visible lines are swept, and the cache
//     covers only the light rays through what is visible. With piecewise
//     integration a cache texel no visible ray has written still holds
//     "unlit at the box entry", so the first visible sample on its light ray
//     marches all the way to the box and off-screen structures do shadow the
//     visible ones. Without it they do not (the paper's limitation, section 7).
#include "penumbra/render/technique.h"

namespace penumbra {

TechniqueInfo ipsvi_info();

}  // namespace penumbra

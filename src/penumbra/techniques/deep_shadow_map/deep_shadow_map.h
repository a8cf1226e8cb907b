#pragma once
// deep-shadow-map: deep shadow maps (Lokovic & Veach 2000) for DVR
// (Hadwiger et al. 2006), the technique Weidner & Linsen (2018) compare CSSM
// against, with three nodes per texel in their comparison. Per texel, the
// transmittance of the light ray as a function of depth, per colour channel
// (the colour model of light_ray.h: chromatic by default, the CSSM paper's
// 1 - alpha (1 - t), or grey 1 - alpha),
// compressed to N nodes (depth, r, g, b) by an error-bounded greedy
// (deep_shadow_compression.h); a lookup interpolates between the nodes.
//
// Soft shadows from the light's size (issue 18, light_space/pcss.h): with
// soft = auto (an option; default off, see light_map_technique.h), a light with a
// size (distant angle_deg, sphere/disk radius) gets a PCSS filter: a blocker
// search sized by the light, the mean blocker depth d_b, then the mean of 48 nearest-texel functions at the sample's depth over a
// disk of half-width w = (d_r - d_b) tan(theta) (distant; a gaussian light
// as the uniform disk of equal variance, tan = 2 tan(sigma)) or
// w = R (d_r - d_b) / d_b (sphere, disk: similar triangles), d_r the
// sample's depth. Under an opaque edge that is the disk light's penumbra,
// full width 2 d tan(theta), 10-90 % width 1.3741 d tan(theta) (measured
// +12.6 % at 3 degrees, +7.2 % at 8; docs/shadow-maps.md). Lights without a size, or soft = off:
// the paper's filter as before.
//
// Parameters
//   resolution  map texels per side (half per cube face), 256..4096
//   nodes       nodes per texel, 2..16 (4 floats each)
//   tolerance   compression error bound; raised per texel (in steps of
//               1.64x, up to 32x) until the function fits in `nodes`; the
//               value behind the last node (what receivers behind the
//               volume read) is kept exact
//   filter      nearest texel, or bilinear over the four nearest texels
//   slope_bias  lookups move toward the light by this many times the
//               occluder's depth change over the texels read (against
//               moire on grazing surfaces; deep_shadow_map_kernels.h)
//   colored, color_model, saturation
//               the colour model (light_ray.h, light_map_technique.h)
//   soft          auto: the PCSS filter for lights with a size; off (default):
//                 the paper's filter (light_map_technique.h)
// Passes
//   prepare: one map per light, rebuilt only when the data, TF (or shadow
//            TF), lights, clip planes, step, resolution, nodes, tolerance or
//            colour model change
//   render:  one ray-casting pass; per lit sample one (or four) node
//            evaluations
#include "penumbra/render/technique.h"

namespace penumbra {

TechniqueInfo deep_shadow_map_info();

}  // namespace penumbra

#pragma once
// shadow-map: the traditional shadow map that Weidner & Linsen (2018,
// "Colored Stochastic Shadow Mapping for Direct Volume Rendering", section 4)
// compare against, for DVR: per texel the depth at which the accumulated
// opacity along the light ray passes a threshold (0.5 in the paper); a
// sample is lit when it lies in front of that depth. Opaque structures cast
// correct hard shadows; translucent ones cast either none or full shadows.
//
// Soft shadows from the light's size (issue 18, light_space/pcss.h): with
// soft = auto (an option; default off, see light_map_technique.h) and pcf_radius unset (< 0, the default), a light with a
// size (distant angle_deg, sphere/disk radius) gets a PCSS filter: a blocker
// search sized by the light, the mean blocker depth d_b, then 48 depth tests over a
// disk of half-width w = (d_r - d_b) tan(theta) (distant; a gaussian light
// as the uniform disk of equal variance, tan = 2 tan(sigma)) or
// w = R (d_r - d_b) / d_b (sphere, disk: similar triangles), d_r the
// sample's depth. Under an opaque edge that is the disk light's penumbra,
// full width 2 d tan(theta), 10-90 % width 1.3741 d tan(theta) (measured
// +5.8 % at 3 degrees, +2.1 % at 8; docs/shadow-maps.md). Lights without a size, soft = off or pcf_radius set:
// the paper's filter as before.
//
// Parameters
//   resolution   map texels per side (half per cube face for a point light in or
//                near the volume), 256..4096
//   threshold    accumulated opacity that counts as the occluder's depth
//   pcf_radius   percentage-closer filtering over (2 r + 1)^2 texels (< 0: unset)
//                (0 = one binary test)
//   depth_bias   added to the stored depth (voxels) against self-shadowing
//   slope_bias   plus this many times the stored depth's change over the
//                texels a tap stands for (against acne on grazing surfaces)
//   soft          auto: the PCSS filter for lights with a size; off (default):
//                 the paper's filter (light_map_technique.h)
// Passes
//   prepare: one map per light (light_space/: orthographic for directional
//            lights, perspective or a cube map for point lights), rebuilt
//            only when the data, TF (or shadow TF), lights, clip planes,
//            step, resolution or threshold change
//   render:  one ray-casting pass; per lit sample one depth test per PCF tap
#include "penumbra/render/technique.h"

namespace penumbra {

TechniqueInfo shadow_map_info();

}  // namespace penumbra

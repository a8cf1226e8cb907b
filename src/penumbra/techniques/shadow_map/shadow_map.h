#pragma once
// shadow-map: the traditional shadow map that Weidner & Linsen (2018,
// "Colored Stochastic Shadow Mapping for Direct Volume Rendering", section 4)
// compare against, for DVR: per texel the depth at which the accumulated
// opacity along the light ray passes a threshold (0.5 in the paper); a
// sample is lit when it lies in front of that depth. Opaque structures cast
// correct hard shadows; translucent ones cast either none or full shadows.
//
// Parameters
//   resolution   map texels per side (half per cube face for a point light in or
//                near the volume), 256..4096
//   threshold    accumulated opacity that counts as the occluder's depth
//   pcf_radius   percentage-closer filtering over (2 r + 1)^2 texels
//                (0 = one binary test)
//   depth_bias   added to the stored depth (voxels) against self-shadowing
//   slope_bias   plus this many times the stored depth's change over the
//                texels a tap stands for (against acne on grazing surfaces)
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

#pragma once
// deep-shadow-map: deep shadow maps (Lokovic & Veach 2000) for DVR
// (Hadwiger et al. 2006), the technique Weidner & Linsen (2018) compare CSSM
// against, with three nodes per texel in their comparison. Per texel, the
// transmittance of the light ray as a function of depth, per colour channel
// (light_ray.h: with `colored`, a segment of opacity alpha and TF colour t
// transmits 1 - alpha (1 - t), the CSSM paper's model; without, 1 - alpha),
// compressed to N nodes (depth, r, g, b) by an error-bounded greedy
// (deep_shadow_compression.h); a lookup interpolates between the nodes.
//
// Parameters
//   resolution  map texels per side (half per cube face), 256..4096
//   nodes       nodes per texel, 2..16 (4 floats each)
//   tolerance   compression error bound; raised per texel (in steps of
//               1.64x, up to 32x) until the function fits in `nodes`; the
//               value behind the last node (what receivers behind the
//               volume read) is kept exact
//   colored     transport colour: shadows take the TF colour of what they
//               pass through (false: grey, the shadow-rays transmittance)
//   filter      nearest texel, or bilinear over the four nearest texels
// Passes
//   prepare: one map per light, rebuilt only when the data, TF (or shadow
//            TF), lights, clip planes, step, resolution, nodes, tolerance or
//            colored change
//   render:  one ray-casting pass; per lit sample one (or four) node
//            evaluations
#include "penumbra/render/technique.h"

namespace penumbra {

TechniqueInfo deep_shadow_map_info();

}  // namespace penumbra

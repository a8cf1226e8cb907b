#pragma once
// cssm: colored stochastic shadow maps for DVR (Weidner & Linsen 2018,
// "Colored Stochastic Shadow Mapping for Direct Volume Rendering", after
// McGuire & Enderton 2011). Per texel and colour channel one photon is sent
// from the light and stopped in segment i with probability
// alpha_i (1 - t_i,lambda) (t: the TF colour, the transport colour), the
// depth where it stops is stored (3 floats per texel); a sample's shadow
// factor averages m depth tests at offsets around its texel (Tables 1, 2;
// cssm_kernels.h). In expectation the shadow factor is the coloured
// transmittance of light_ray.h; the offsets trade its noise for blur.
//
// Parameters
//   resolution    map texels per side (half per cube face), 256..4096
//   offsets       7, 13 (the paper's default) or 21 lookups (cssm_offsets.h)
//   offset_scale  multiplies the offsets, which are in texels of a 1024^2
//                 map and scale with `resolution`
//   seed          the random numbers of the generation (deterministic)
//   colored       transport colour t = TF colour; false: t = 0, grey
//                 shadows whose expectation is the shadow-rays transmittance
// Passes
//   prepare: one map per light, rebuilt only when the data, TF (or shadow
//            TF), lights, clip planes, step, resolution, seed or colored
//            change
//   render:  one ray-casting pass; per lit sample m texel reads
#include "penumbra/render/technique.h"

namespace penumbra {

TechniqueInfo cssm_info();

}  // namespace penumbra

#pragma once
// cssm: colored stochastic shadow maps for DVR (Weidner & Linsen 2018,
// "Colored Stochastic Shadow Mapping for Direct Volume Rendering", after
// McGuire & Enderton 2011). Per texel and colour channel one photon is sent
// from the light and stopped in segment i with probability rho_i (the colour
// model of light_ray.h: chromatic by default, the paper's alpha_i (1 - t_i)
// or grey), the depth where it stops is stored, with the ray's entry into
// the occluder (4 floats per texel); a sample's shadow factor averages m
// depth tests at offsets around its texel (Tables 1, 2; cssm_kernels.h). In
// expectation the shadow factor is the transmittance of the texels read;
// the offsets trade its noise for blur.
//
// Soft shadows from the light's size (issue 18, light_space/pcss.h): with
// soft = auto (an option; default off, see light_map_technique.h) and offset_scale unset (< 0, the default), a light with a
// size (distant angle_deg, sphere/disk radius) gets a PCSS filter: a blocker
// search sized by the light, the mean blocker depth d_b, then 48 stochastic tests at the sample's depth over a
// disk of half-width w = (d_r - d_b) tan(theta) (distant; a gaussian light
// as the uniform disk of equal variance, tan = 2 tan(sigma)) or
// w = R (d_r - d_b) / d_b (sphere, disk: similar triangles), d_r the
// sample's depth. Under an opaque edge that is the disk light's penumbra,
// full width 2 d tan(theta), 10-90 % width 1.3741 d tan(theta) (measured
// +12.1 % at 3 degrees, +6.1 % at 8; docs/shadow-maps.md). Lights without a size, soft = off or offset_scale set:
// the paper's filter as before.
//
// Parameters
//   resolution    map texels per side (half per cube face), 256..4096
//   offsets       7, 13 (the paper's default), 21 or 37 lookups (cssm_offsets.h)
//   offset_scale  multiplies the offsets, which are in texels of the map (< 0:
//                 unset, 1 or PCSS, see above; a
//                 finer map blurs less: resolution is a quality control)
//   filter        depth-aware (default): each tap read at the sample's depth
//                 below the occluder's entry plane, taps off that plane
//                 dropped (no leak where the light grazes a surface); paper:
//                 every tap at the sample's depth
//   seed          the random numbers of the generation (deterministic)
//   colored, color_model, saturation
//                 the colour model (light_ray.h, light_map_technique.h)
//   soft          auto: the PCSS filter for lights with a size; off (default):
//                 the paper's filter (light_map_technique.h)
// Passes
//   prepare: one map per light, rebuilt only when the data, TF (or shadow
//            TF), lights, clip planes, step, resolution, seed or colour
//            model change
//   render:  one ray-casting pass; per lit sample 5 + 4 m texel values read
//            (3 m with the paper's filter)
#include "penumbra/render/technique.h"

namespace penumbra {

TechniqueInfo cssm_info();

}  // namespace penumbra

#pragma once
// pathtrace: the Monte Carlo reference every technique is measured against
// (DESIGN.md 1). Unbiased volumetric path tracing on the same sigma_t,
// albedo (material.albedo * TF colour) and Henyey-Greenstein phase function
// as the other techniques: delta tracking for free flights and ratio
// tracking for transmittance (Woodcock et al. 1965; Novak et al. 2014; see
// Novak et al., "Monte Carlo Methods for Volumetric Light Transport
// Simulation", EG STAR 2018), both against the per-macrocell majorants so
// empty space costs nothing; next-event estimation to every light, area and
// environment lights sampled (scene/light_sampling.h); opaque Lambertian
// planes. Light units as in DESIGN-NOTES.md, so `single` mode converges to
// shadow-rays; `ambient` is ignored (compare with scenes that set it to 0).
// The scene's closed meshes are media too, tracked one medium at a time
// (mesh_tracking.h), so every mesh scene of convolution has a reference, on
// either device (the meshes mirrored by backends/cuda/mesh_mirror.h).
//
// Parameters
//   mode          single (default): one scattering event lit by transmittance
//                 only, the model every other technique approximates, so
//                 comparisons measure their error by default; multiple: full
//                 multiple scattering (the physically based target)
//   spp           paths per pixel (the most a pixel takes)
//   target_error  stop a pixel once the standard error of its lightness, and
//                 that of its 8 neighbours, is below this many CIE L* units
//                 (0 = always take spp)
//   min_spp       paths every pixel takes before target_error may stop it
//   max_bounces   scattering events per path in multiple mode (Russian
//                 roulette ends most paths far earlier)
//   seed          the random streams: sample s of pixel p uses stream
//                 (seed, p, s), so images are reproducible on any thread count
//   antialias     random positions inside each pixel instead of its centre
//                 (every other technique samples the centre)
//   progress      progress bar on stderr when it is a terminal
//   progressive   off (default): every render starts a new estimate of spp
//                 paths per pixel (the CLI, compare, bench, Python); on (the
//                 web viewer's server sets it): a render of the same state as
//                 the last one -- the scene's version counters and every
//                 parameter unchanged -- adds spp paths per pixel to the
//                 last estimate, up to max_total_spp. Sample s of a pixel
//                 uses stream (seed, pixel, s) however the paths are split
//                 into renders, so N renders of k spp give exactly the image
//                 of one render of N k spp (with target_error 0; with it, the
//                 same too when k = min_spp * 2^j, where the passes coincide)
//   max_total_spp progressive: the most paths per pixel; once there (or all
//                 pixels met target_error) renders return the estimate as is
// Passes
//   prepare: nothing of its own (the shared macrocell majorants and TF
//            table); notes whether the state differs from the estimate's
//   render:  passes of min_spp, then doubling sample counts (continuing from
//            the estimate's count when progressive); after each pass, pixels
//            whose neighbourhood's error is below target_error stop. Keeps a
//            per-pixel variance estimate (pathtrace_estimate()).
#include "penumbra/render/technique.h"

#include <cstdint>

namespace penumbra {

TechniqueInfo pathtrace_info();

// What the last render() of a pathtrace technique estimated besides the
// image. With `progressive` the estimate may span several renders: the
// counts are of all of them.
struct PathTraceEstimate {
  // Per pixel: rgb = standard error of the mean radiance per channel (+inf
  // where a pixel has fewer than 2 paths); alpha = the number of paths.
  Image standard_error;
  std::uint64_t paths = 0;  // paths in the estimate, all pixels together
  int passes = 0;
  int spp = 0;              // paths a pixel not stopped early has taken
  int renders = 0;          // renders that built the estimate (1 without progressive)
  // Nothing more to add: every pixel met target_error, or spp reached its
  // most (spp; max_total_spp with progressive).
  bool converged = false;
};

// The estimate of `technique`'s last render; nullptr when it is not a
// pathtrace technique or has not rendered yet.
const PathTraceEstimate* pathtrace_estimate(const Technique& technique);

// Standard error in CIE L* units of a pixel's lightness, from its mean
// luminance Y (linear, display white 1) and the standard error of Y:
// sigma_L = dL*/dY * sigma_Y with L* = 116 Y^(1/3) - 16 (903.3 Y near black);
// Y is clamped to [0, 1] as a display clamps it.
double lightness_standard_error(double mean_luminance, double luminance_standard_error);

}  // namespace penumbra

#pragma once
// pathtrace's per-pixel work, the functor both backends run: one pass adds
// paths [taken, target) of a pixel to its running sums. The CPU tile loop
// (pathtrace.cpp) and the CUDA launch (pathtrace_device.cu) call
// trace_pixel_paths; the host decides between passes which pixels have
// converged (PixelAccumulator::done).
#include "penumbra/techniques/pathtrace/path_kernel.h"

#include <cstdint>
#include <vector>

namespace penumbra {

// Running sums of one pixel's paths (double: a pixel may take millions).
struct PixelAccumulator {
  dvec3 sum{0.0};
  dvec3 sum_squares{0.0};
  double luminance_squares = 0.0;
  std::uint32_t paths = 0;
  std::uint32_t hits = 0;
  bool done = false;

  PENUMBRA_HD void add(const PathSample& s) {
    const dvec3 r(s.radiance);
    sum += r;
    sum_squares += r * r;
    const double y = luminance(s.radiance);
    luminance_squares += y * y;
    ++paths;
    hits += s.hit ? 1u : 0u;
  }
};

// One pass over the image: paths [taken, target) of every pixel not done.
struct PathPass {
  int width = 0;
  int height = 0;
  int taken = 0;
  int target = 0;
  std::uint32_t seed = 0;
  bool antialias = false;
};

// Adds the pass's paths of pixel (x, y) to `pixel` (nothing once it is
// done); returns the volume lookups they took. Sample s of the pixel uses
// the random stream (seed, pixel, s) wherever it runs.
template <class Sampler>
PENUMBRA_HD std::uint64_t trace_pixel_paths(const PathKernel<Sampler>& kernel, const PathPass& pass,
                                            PixelAccumulator& pixel, int x, int y) {
  if (pixel.done) return 0;
  std::uint64_t lookups = 0;
  const std::uint32_t index = std::uint32_t(y) * std::uint32_t(pass.width) + std::uint32_t(x);
  for (int s = pass.taken; s < pass.target; ++s) {
    Pcg32 rng = path_rng(pass.seed, index, std::uint32_t(s));
    const float dx = pass.antialias ? rng.next_float() : 0.5f;
    const float dy = pass.antialias ? rng.next_float() : 0.5f;
    const Ray ray = kernel.view->camera.pixel_ray(float(x) + dx, float(y) + dy, pass.width, pass.height);
    pixel.add(kernel.trace(ray, rng, lookups));
  }
  return lookups;
}

// Runs one pass on the CUDA device over `pixels` (width x height, row by
// row): uploads them, launches trace_pixel_paths per pixel, downloads them;
// returns the lookups. `view` and `shadows` are pathtrace's render views
// (their device mirrors persist from pass to pass and frame to frame),
// `meshes` the scene's meshes with their BVHs (backends/cuda/mesh_mirror.h).
// Defined only in builds with the CUDA backend (pathtrace_device.cu).
std::uint64_t trace_paths_device(const RenderView& view, const RenderView& shadows, const MeshesView& meshes,
                                 const PathSettings& settings, const PathPass& pass,
                                 std::vector<PixelAccumulator>& pixels);

}  // namespace penumbra

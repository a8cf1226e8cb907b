#pragma once
// The CPU backend's image loop: primary rays over 16x16 tiles in parallel,
// each pixel marched with the technique's Lighting.
#include "penumbra/base/parallel.h"
#include "penumbra/base/rng.h"
#include "penumbra/render/image.h"
#include "penumbra/render/march.h"

#include <atomic>
#include <cstdint>

namespace penumbra {

// Per-pixel sample offset: 0.5 (midpoint) or a hashed random value in [0, 1).
PENUMBRA_HD inline float pixel_sample_offset(const RenderView& v, int x, int y) {
  if (!v.jitter) return 0.5f;
  Pcg32 rng(mix_bits((std::uint64_t(std::uint32_t(y)) << 32) | std::uint32_t(x)));
  return rng.next_float();
}

struct RenderStats {
  std::uint64_t samples = 0;
  std::uint64_t rays = 0;
  std::uint64_t passes = 0;  // sweep steps of sweeping techniques (convolution's slabs); 0 for the others
};

// Renders every pixel with march_ray. make_lighting(sampler) returns the
// technique's Lighting for the volume's typed sampler (called once; the voxel
// type is dispatched once per image, not per sample).
template <class MakeLighting>
void render_image(const RenderView& v, const MakeLighting& make_lighting, Image& image, RenderStats* stats = nullptr) {
  if (image.width() != v.width || image.height() != v.height) image = Image(v.width, v.height);
  std::atomic<std::uint64_t> total_samples{0};
  with_sampler(v.volume, [&](const auto& sampler) {
    const auto lighting = make_lighting(sampler);
    parallel_for_tiles(v.width, v.height, 16, [&](int x0, int y0, int x1, int y1) {
      RayStats tile_stats;
      for (int y = y0; y < y1; ++y) {
        for (int x = x0; x < x1; ++x) {
          const Ray ray = v.camera.pixel_ray(float(x) + 0.5f, float(y) + 0.5f, v.width, v.height);
          image.at(x, y) = march_ray(v, sampler, ray, pixel_sample_offset(v, x, y), lighting, tile_stats);
        }
      }
      total_samples.fetch_add(tile_stats.samples, std::memory_order_relaxed);
    });
    return 0;
  });
  if (stats) {
    stats->samples += total_samples.load();
    stats->rays += std::uint64_t(v.width) * std::uint64_t(v.height);
  }
}

}  // namespace penumbra

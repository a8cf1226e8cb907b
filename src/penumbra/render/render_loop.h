#pragma once
// The image loop: each pixel marched with the technique's Lighting
// (march_pixel). On the CUDA device one thread per pixel when the Lighting
// has a device path and CUDA is active (backends/cuda/launch.cuh); else on
// the CPU, primary rays over 16x16 tiles in parallel, as packets of 8 or 16
// rays (backends/cpu/packet_render.h) when the Lighting has a packet path
// and packets are on, else one ray at a time.
#include "penumbra/backends/cpu/packets.h"
#include "penumbra/backends/device.h"
#include "penumbra/base/parallel.h"
#include "penumbra/base/rng.h"
#include "penumbra/render/image.h"
#include "penumbra/render/march.h"

#include <atomic>
#include <cstdint>
#include <type_traits>

namespace penumbra {

// A hashed random value in [0, 1) per pixel (x, y), the same on every backend.
PENUMBRA_HD inline float pixel_hash_offset(int x, int y) {
  Pcg32 rng(mix_bits((std::uint64_t(std::uint32_t(y)) << 32) | std::uint32_t(x)));
  return rng.next_float();
}

// Per-pixel sample offset: 0.5 (midpoint) or the pixel's hashed value.
PENUMBRA_HD inline float pixel_sample_offset(const RenderView& v, int x, int y) {
  return v.jitter ? pixel_hash_offset(x, y) : 0.5f;
}

// The per-pixel functor both backends run: the primary ray through the
// centre of pixel (x, y), marched with `lighting`.
template <class Sampler, class Lighting>
PENUMBRA_HD vec4 march_pixel(const RenderView& v, const Sampler& sampler, const Lighting& lighting, int x, int y,
                             RayStats& stats) {
  const Ray ray = v.camera.pixel_ray(float(x) + 0.5f, float(y) + 0.5f, v.width, v.height);
  return march_ray(v, sampler, ray, pixel_sample_offset(v, x, y), lighting, stats);
}

struct RenderStats {
  std::uint64_t samples = 0;
  std::uint64_t rays = 0;
  std::uint64_t steps = 0;   // packet steps of the shared loop's viewing rays (see RayStats)
  std::uint64_t passes = 0;  // sweep steps of sweeping techniques (convolution's slabs); 0 for the others
  SimdTarget simd = SimdTarget::Scalar;  // the packets the shared loop ran as (Scalar: one ray at a time)
  Device device = Device::Cpu;           // where the shared loop ran
};

// Renders with a Lighting's packet path when it has one and `view` can run
// as packets on the active target, and returns that target; Scalar (nothing
// rendered) when the caller must render one ray at a time.
template <class Lighting>
SimdTarget render_image_packets([[maybe_unused]] const RenderView& v, [[maybe_unused]] const Lighting& lighting,
                                [[maybe_unused]] Image& image, [[maybe_unused]] RayStats& stats) {
  if constexpr (PacketLighting<Lighting>::value) {
    const SimdTarget target = packet_target(v);
    switch (target) {
#if defined(PENUMBRA_SIMD_AVX3)
      case SimdTarget::Avx3: render_packets<SimdTarget::Avx3>(v, lighting, image, stats); return target;
#endif
#if defined(PENUMBRA_SIMD_AVX2)
      case SimdTarget::Avx2: render_packets<SimdTarget::Avx2>(v, lighting, image, stats); return target;
#endif
      default: break;
    }
  }
  return SimdTarget::Scalar;
}

// Renders every pixel with march_ray. make_lighting(sampler) returns the
// technique's Lighting for the volume's typed sampler (called once; the voxel
// type is dispatched once per image, not per sample).
template <class MakeLighting>
void render_image(const RenderView& v, const MakeLighting& make_lighting, Image& image, RenderStats* stats = nullptr) {
  if (image.width() != v.width || image.height() != v.height) image = Image(v.width, v.height);
  RayStats totals;
  SimdTarget simd = SimdTarget::Scalar;
  Device device = Device::Cpu;
  with_sampler(v.volume, [&](const auto& sampler) {
    const auto lighting = make_lighting(sampler);
    if constexpr (DeviceLighting<std::remove_cv_t<decltype(lighting)>>::value) {
      if (active_device() == Device::Cuda) {
        render_device(v, lighting, image, totals);
        device = Device::Cuda;
        return 0;
      }
    }
    simd = render_image_packets(v, lighting, image, totals);
    if (simd != SimdTarget::Scalar) return 0;
    std::atomic<std::uint64_t> total_samples{0}, total_steps{0};
    parallel_for_tiles(v.width, v.height, 16, [&](int x0, int y0, int x1, int y1) {
      RayStats tile_stats;
      for (int y = y0; y < y1; ++y) {
        for (int x = x0; x < x1; ++x) {
          image.at(x, y) = march_pixel(v, sampler, lighting, x, y, tile_stats);
        }
      }
      total_samples.fetch_add(tile_stats.samples, std::memory_order_relaxed);
      total_steps.fetch_add(tile_stats.steps, std::memory_order_relaxed);
    });
    totals.samples = total_samples.load();
    totals.steps = total_steps.load();
    return 0;
  });
  if (stats) {
    stats->samples += totals.samples;
    stats->steps += totals.steps;
    stats->rays += std::uint64_t(v.width) * std::uint64_t(v.height);
    stats->simd = simd;
    stats->device = device;
  }
}

}  // namespace penumbra

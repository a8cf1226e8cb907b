#pragma once
// The isosurface image loop: one ray per pixel to the first iso crossing (or
// the nearest opaque plane), shaded by IsosurfaceShader. It mirrors
// render_image (render_loop.h), which composites DVR samples and so cannot
// stop at a surface: over the CPU's tiles, or on the CUDA device with the
// same per-pixel functor (isosurface_pixel_at).
#include "penumbra/backends/device.h"
#include "penumbra/base/parallel.h"
#include "penumbra/render/image.h"
#include "penumbra/render/render_loop.h"
#include "penumbra/techniques/occlusion_map/occlusion_shading.h"

#include <atomic>

namespace penumbra {

template <int K, class Sampler>
PENUMBRA_HD vec4 isosurface_pixel(const IsosurfaceShader<K, Sampler>& shader, const Ray& ray, std::uint64_t& samples,
                                  SoftShadowQueries* deferred = nullptr) {
  const RenderView& v = *shader.setup->iso_view;
  float t_plane = kInfinity;
  const int plane = nearest_plane(v, ray, kInfinity, t_plane);
  const Interval interval = volume_interval(v, ray, 0.0f, t_plane);
  const float t = interval.empty()
                      ? kInfinity
                      : first_iso_crossing(v, shader.sampler, ray, interval, shader.setup->iso, samples);
  if (t < kInfinity) return vec4(shader.surface(ray.at(t), ray.direction, deferred), 1.0f);
  if (plane >= 0) return vec4(shader.plane(PlaneHit{ray.at(t_plane), plane, ray.direction}, deferred), 1.0f);
  return vec4(v.background, 0.0f);
}

// The per-pixel functor both backends run: pixel (x, y)'s ray, its shaded
// hit written to out; returns the samples taken.
template <int K, class Sampler>
PENUMBRA_HD std::uint64_t isosurface_pixel_at(const IsosurfaceShader<K, Sampler>& shader, vec4* out, int x, int y,
                                              SoftShadowQueries* deferred = nullptr) {
  const RenderView& v = *shader.setup->iso_view;
  const Ray ray = v.camera.pixel_ray(float(x) + 0.5f, float(y) + 0.5f, v.width, v.height);
  std::uint64_t samples = 0;
  if (deferred) deferred->pixel = y * v.width + x;
  out[std::size_t(y) * std::size_t(v.width) + std::size_t(x)] = isosurface_pixel(shader, ray, samples, deferred);
  return samples;
}

// Renders the isosurface image on the CUDA device into `image` (sized by
// the caller); returns the samples. Defined only in builds with the CUDA
// backend (occlusion_map_device.cu), for K = 2 and 4.
template <int K> std::uint64_t render_isosurface_device(const OcclusionShadingSetup<K>& setup, Image& image);

// The soft-shadow march of `target` (soft_shadow_batch.h), or nullptr where
// this build has none. (Not in soft_shadow_batch.h: a SIMD unit must not
// instantiate the other target's march.)
inline SoftShadowMarch soft_shadow_march(SimdTarget target) {
  return simd_unit_function(target, []<SimdTarget T>() { return &march_soft_shadows<T>; });
}

// One tile with its soft shadows marched as packets (soft_shadow_batch.h):
// the pixels shaded with their marches recorded, the marches run by `march`,
// each light's share added back scaled by its visibility.
template <class Sampler>
std::uint64_t render_isosurface_tile_packets(const IsosurfaceShader<2, Sampler>& shader, SoftShadowMarch march,
                                             Image& image, int x0, int y0, int x1, int y1) {
  const OcclusionShadingSetup<2>& setup = *shader.setup;
  const RenderView& v = *setup.iso_view;
  SoftShadowBatch batch((x1 - x0) * (y1 - y0), v.light_count);
  SoftShadowQueries queries = batch.queries();
  std::uint64_t samples = 0;
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) samples += isosurface_pixel_at(shader, image.data(), x, y, &queries);
  }
  SoftShadowBatch::pad(queries);
  march(setup.queries, setup.normalise(setup.iso), queries, batch.visibility());
  const float* visibility = batch.visibility();
  for (int i = 0; i < queries.count; ++i) {
    const int pixel = queries.pixels[i];
    vec4& out = image.at(pixel % v.width, pixel / v.width);
    out += vec4(queries.shares[i] * visibility[i], 0.0f);
  }
  return samples;
}

template <int K>
void render_isosurface_image(const OcclusionShadingSetup<K>& setup, Image& image, RenderStats* stats) {
  const RenderView& v = *setup.iso_view;
  if (image.width() != v.width || image.height() != v.height) image = Image(v.width, v.height);
#if defined(PENUMBRA_HAVE_CUDA)
  if (active_device() == Device::Cuda) {
    const std::uint64_t samples = render_isosurface_device(setup, image);
    if (stats) {
      stats->samples += samples;
      stats->rays += std::uint64_t(v.width) * std::uint64_t(v.height);
      stats->device = Device::Cuda;
    }
    return;
  }
#endif
  // Soft shadows (two moments) march as packets where this CPU has them.
  SimdTarget simd = SimdTarget::Scalar;
  SoftShadowMarch march = nullptr;
  if constexpr (K == 2) {
    if (setup.shadows == ShadowMode::Soft && setup.queries.packets_fit()) {
      simd = active_simd_target();
      march = soft_shadow_march(simd);
      if (!march) simd = SimdTarget::Scalar;
    }
  }
  std::atomic<std::uint64_t> total_samples{0};
  with_sampler(v.volume, [&](const auto& sampler) {
    const IsosurfaceShader<K, std::decay_t<decltype(sampler)>> shader{&setup, sampler};
    parallel_for_tiles(v.width, v.height, 16, [&](int x0, int y0, int x1, int y1) {
      std::uint64_t samples = 0;
      if constexpr (K == 2) {
        if (march) {
          total_samples.fetch_add(render_isosurface_tile_packets(shader, march, image, x0, y0, x1, y1),
                                  std::memory_order_relaxed);
          return;
        }
      }
      for (int y = y0; y < y1; ++y) {
        for (int x = x0; x < x1; ++x) samples += isosurface_pixel_at(shader, image.data(), x, y);
      }
      total_samples.fetch_add(samples, std::memory_order_relaxed);
    });
    return 0;
  });
  if (stats) {
    stats->simd = simd;
    stats->samples += total_samples.load();
    stats->rays += std::uint64_t(v.width) * std::uint64_t(v.height);
  }
}

}  // namespace penumbra

#pragma once
// The CUDA backend's launch: the per-pixel functor the CPU backend runs over
// tiles (march_pixel, render/render_loop.h), one thread per pixel. The only
// CUDA-only code is this launch and the device memory (device_cache.h,
// device_mirror.h); every kernel body is the technique's shared header.
//
// A technique's .cu unit includes its visibility header and this file and
// instantiates its Lightings with PENUMBRA_INSTANTIATE_DEVICE(type); a
// technique with its own image loop (pathtrace, occlusion-map) launches its
// per-pixel functor, the one its CPU tile loop calls, with launch_pixels.
#include "penumbra/backends/cuda/device_cache.h"
#include "penumbra/backends/cuda/device_mirror.h"
#include "penumbra/backends/device.h"
#include "penumbra/base/error.h"
#include "penumbra/render/render_loop.h"

#include <cuda_runtime.h>

#include <cstdint>
#include <memory>

namespace penumbra {

// The launch: f(x, y) once per pixel of a width x height image, one thread
// per pixel; returns the sum of what the calls return (the samples or
// lookups they took). Every device render goes through it: march_pixel for
// the shared loop (MarchPixels below) and the per-pixel functors of the
// techniques with their own image loops (pathtrace, occlusion-map).
template <class PixelFunctor>
__global__ void for_each_pixel(int width, int height, PixelFunctor f, unsigned long long* counter) {
  const int x = int(blockIdx.x * blockDim.x + threadIdx.x);
  const int y = int(blockIdx.y * blockDim.y + threadIdx.y);
  if (x >= width || y >= height) return;
  atomicAdd(counter, static_cast<unsigned long long>(f(x, y)));
}

// The shared loop's per-pixel functor on the device. Samples every voxel
// type through one switch (uniform across a warp), so a Lighting compiles
// once, not once per voxel type.
template <class Lighting> struct MarchPixels {
  const RenderView* view;
  Lighting lighting;
  vec4* out;

  __device__ std::uint64_t operator()(int x, int y) const {
    const RenderView& v = *view;
    const AnyVoxelSampler sampler(v.volume.data, v.volume.dims, v.volume.type);
    RayStats stats;
    out[std::size_t(y) * std::size_t(v.width) + std::size_t(x)] = march_pixel(v, sampler, lighting, x, y, stats);
    return stats.samples;
  }
};

// The DeviceCache of the technique state that made `view`.
inline DeviceCache& device_cache_of(const RenderView& view) {
  if (!view.device_state) throw Error("cuda: the render view has no device state (made outside SceneResources)");
  std::shared_ptr<void>& state = *view.device_state;
  if (!state) state = std::make_shared<DeviceCache>(cuda_memory());
  return *static_cast<DeviceCache*>(state.get());
}

// Runs f over every pixel (for_each_pixel) and waits for it; returns the
// sum of its counts. `cache` holds the counter for this frame.
template <class PixelFunctor>
std::uint64_t launch_pixels(DeviceCache& cache, int width, int height, const PixelFunctor& f) {
  auto* counter = static_cast<unsigned long long*>(cache.frame_zeroed(sizeof(unsigned long long), "counters"));
  if (width > 0 && height > 0) {
    const dim3 block(16, 8);
    const dim3 grid((unsigned(width) + block.x - 1) / block.x, (unsigned(height) + block.y - 1) / block.y);
    for_each_pixel<<<grid, block>>>(width, height, f, counter);
    check_cuda(cudaGetLastError(), "kernel launch");
  }
  unsigned long long count = 0;
  check_cuda(cudaMemcpy(&count, counter, sizeof(count), cudaMemcpyDeviceToHost), "cudaMemcpy (counters)");
  return count;
}

// Launches the functor make_functor(out) returns over the image, out being
// device memory for one vec4 per pixel, and copies the image back; returns
// the functor's counts. For the per-pixel functors that write the image.
template <class MakeFunctor>
std::uint64_t launch_image(DeviceCache& cache, int width, int height, Image& image, const MakeFunctor& make_functor) {
  const std::size_t pixels = std::size_t(width) * std::size_t(height);
  auto* out = static_cast<vec4*>(cache.scratch(pixels * sizeof(vec4), "the image"));
  const std::uint64_t count = launch_pixels(cache, width, height, make_functor(out));
  if (pixels > 0) {
    check_cuda(cudaMemcpy(image.data(), out, pixels * sizeof(vec4), cudaMemcpyDeviceToHost), "cudaMemcpy (image)");
  }
  return count;
}

template <class Lighting>
void render_device(const RenderView& view, const Lighting& lighting, Image& image, RayStats& stats) {
  DeviceCache& cache = device_cache_of(view);
  cache.begin_frame();
  DeviceMirror mirror(cache, view);
  const RenderView* device_view = mirror.view(view);
  const Lighting device_lighting = lighting.on_device(mirror);
  stats.samples += launch_image(cache, view.width, view.height, image, [&](vec4* out) {
    return MarchPixels<Lighting>{device_view, device_lighting, out};
  });
  cache.end_frame();
}

}  // namespace penumbra

// Instantiates render_device for `...` (a Lighting declared with
// PENUMBRA_DEVICE_LIGHTING, named as from inside namespace penumbra); at
// global scope in a .cu unit. (No using-directive at global scope: it would
// make the CUDA headers' math calls ambiguous with base/lanes.h's.)
#define PENUMBRA_INSTANTIATE_DEVICE(...)                                                       \
  namespace penumbra {                                                                         \
  template void render_device<__VA_ARGS__>(const RenderView&, const __VA_ARGS__&, Image&, RayStats&); \
  }                                                                                            \
  static_assert(true)

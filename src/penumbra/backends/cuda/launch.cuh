#pragma once
// The CUDA backend's launch: the per-pixel functor the CPU backend runs over
// tiles (march_pixel, render/render_loop.h), one thread per pixel. The only
// CUDA-only code is this launch and the device memory (device_cache.h,
// device_mirror.h); every kernel body is the technique's shared header.
//
// A technique's .cu unit includes its visibility header and this file and
// instantiates its Lightings with PENUMBRA_INSTANTIATE_DEVICE(type).
#include "penumbra/backends/cuda/device_cache.h"
#include "penumbra/backends/cuda/device_mirror.h"
#include "penumbra/backends/device.h"
#include "penumbra/base/error.h"
#include "penumbra/render/render_loop.h"

#include <cuda_runtime.h>

#include <memory>

namespace penumbra {

// Samples every voxel type through one switch (uniform across a warp), so a
// Lighting compiles once, not once per voxel type.
template <class Lighting>
__global__ void march_pixels(const RenderView* view, Lighting lighting, vec4* out, unsigned long long* samples) {
  const int x = int(blockIdx.x * blockDim.x + threadIdx.x);
  const int y = int(blockIdx.y * blockDim.y + threadIdx.y);
  const RenderView& v = *view;
  if (x >= v.width || y >= v.height) return;
  const AnyVoxelSampler sampler(v.volume.data, v.volume.dims, v.volume.type);
  RayStats stats;
  out[std::size_t(y) * v.width + x] = march_pixel(v, sampler, lighting, x, y, stats);
  atomicAdd(samples, static_cast<unsigned long long>(stats.samples));
}

// The DeviceCache of the technique state that made `view`.
inline DeviceCache& device_cache_of(const RenderView& view) {
  if (!view.device_state) throw Error("cuda: the render view has no device state (made outside SceneResources)");
  std::shared_ptr<void>& state = *view.device_state;
  if (!state) state = std::make_shared<DeviceCache>(cuda_memory());
  return *static_cast<DeviceCache*>(state.get());
}

template <class Lighting>
void render_device(const RenderView& view, const Lighting& lighting, Image& image, RayStats& stats) {
  DeviceCache& cache = device_cache_of(view);
  cache.begin_frame();
  DeviceMirror mirror(cache, view);
  const RenderView* device_view = mirror.view(view);
  const Lighting device_lighting = lighting.on_device(mirror);
  const std::size_t pixels = std::size_t(view.width) * std::size_t(view.height);
  auto* out = static_cast<vec4*>(cache.scratch(pixels * sizeof(vec4), "the image"));
  auto* samples = static_cast<unsigned long long*>(cache.frame_zeroed(sizeof(unsigned long long), "counters"));
  const dim3 block(16, 8);
  const dim3 grid((unsigned(view.width) + block.x - 1) / block.x, (unsigned(view.height) + block.y - 1) / block.y);
  if (pixels > 0) {
    march_pixels<<<grid, block>>>(device_view, device_lighting, out, samples);
    check_cuda(cudaGetLastError(), "kernel launch");
    check_cuda(cudaMemcpy(image.data(), out, pixels * sizeof(vec4), cudaMemcpyDeviceToHost), "cudaMemcpy (image)");
  }
  unsigned long long count = 0;
  check_cuda(cudaMemcpy(&count, samples, sizeof(count), cudaMemcpyDeviceToHost), "cudaMemcpy (counters)");
  stats.samples += count;
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

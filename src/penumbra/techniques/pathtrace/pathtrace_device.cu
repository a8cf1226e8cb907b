// CUDA unit (cmake/PenumbraCuda.cmake): pathtrace's passes on the device,
// through the shared launch (backends/cuda/launch.cuh) and the per-pixel
// functor of the CPU tile loop (path_pixels.h).
#include "penumbra/backends/cuda/launch.cuh"
#include "penumbra/backends/cuda/mesh_mirror.h"
#include "penumbra/techniques/pathtrace/path_pixels.h"

namespace penumbra {
namespace {

struct DevicePathPixels {
  const RenderView* view;
  const RenderView* shadows;
  PathSettings settings;
  PathPass pass;
  PixelAccumulator* pixels;
  MeshesView meshes;

  __device__ std::uint64_t operator()(int x, int y) const {
    const AnyVoxelSampler sampler(view->volume.data, view->volume.dims, view->volume.type);
    const PathKernel<AnyVoxelSampler> kernel{view, shadows, sampler, settings, meshes};
    return trace_pixel_paths(kernel, pass, pixels[std::size_t(y) * std::size_t(pass.width) + std::size_t(x)], x, y);
  }
};

}  // namespace

std::uint64_t trace_paths_device(const RenderView& view, const RenderView& shadows, const MeshesView& meshes,
                                 const PathSettings& settings, const PathPass& pass,
                                 std::vector<PixelAccumulator>& pixels) {
  DeviceCache& cache = device_cache_of(view);
  cache.begin_frame();
  DeviceMirror mirror(cache, view);
  const std::size_t bytes = pixels.size() * sizeof(PixelAccumulator);
  auto* device_pixels = static_cast<PixelAccumulator*>(cache.scratch(bytes, "the path accumulators"));
  if (bytes > 0) {
    check_cuda(cudaMemcpy(device_pixels, pixels.data(), bytes, cudaMemcpyHostToDevice), "cudaMemcpy (accumulators)");
  }
  const DevicePathPixels functor{mirror.view(view), mirror.view(shadows), settings, pass, device_pixels,
                                 mirror_meshes(mirror, meshes)};
  const std::uint64_t lookups = launch_pixels(cache, pass.width, pass.height, functor);
  if (bytes > 0) {
    check_cuda(cudaMemcpy(pixels.data(), device_pixels, bytes, cudaMemcpyDeviceToHost), "cudaMemcpy (accumulators)");
  }
  cache.end_frame();
  return lookups;
}

}  // namespace penumbra

// CUDA unit (cmake/PenumbraCuda.cmake): occlusion-map's isosurface image on
// the device, through the shared launch (backends/cuda/launch.cuh) and the
// per-pixel functor of the CPU tile loop (isosurface_render.h); DVR mode
// through the shared loop's device path with DvrOcclusionLighting.
#include "penumbra/backends/cuda/launch.cuh"
#include "penumbra/techniques/occlusion_map/isosurface_render.h"

namespace penumbra {
namespace {

template <int K> struct IsosurfacePixels {
  const OcclusionShadingSetup<K>* setup;
  vec4* out;

  __device__ std::uint64_t operator()(int x, int y) const {
    const VolumeView& volume = setup->iso_view->volume;
    const IsosurfaceShader<K, AnyVoxelSampler> shader{setup, AnyVoxelSampler(volume.data, volume.dims, volume.type)};
    return isosurface_pixel_at(shader, out, x, y);
  }
};

}  // namespace

template <int K> std::uint64_t render_isosurface_device(const OcclusionShadingSetup<K>& setup, Image& image) {
  const RenderView& view = *setup.lit_view;
  DeviceCache& cache = device_cache_of(view);
  cache.begin_frame();
  DeviceMirror mirror(cache, view);
  const OcclusionShadingSetup<K>* device_setup = setup.on_device(mirror);
  const std::uint64_t samples = launch_image(cache, view.width, view.height, image, [&](vec4* out) {
    return IsosurfacePixels<K>{device_setup, out};
  });
  cache.end_frame();
  return samples;
}

template std::uint64_t render_isosurface_device<2>(const OcclusionShadingSetup<2>&, Image&);
template std::uint64_t render_isosurface_device<4>(const OcclusionShadingSetup<4>&, Image&);

}  // namespace penumbra

PENUMBRA_INSTANTIATE_DEVICE(DvrOcclusionLighting<2, AnyVoxelSampler>);
PENUMBRA_INSTANTIATE_DEVICE(DvrOcclusionLighting<4, AnyVoxelSampler>);

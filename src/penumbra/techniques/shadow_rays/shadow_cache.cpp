#include "penumbra/techniques/shadow_rays/shadow_cache.h"

#include "penumbra/base/parallel.h"

namespace penumbra {

Volume build_shadow_cache(const RenderView& v, int light_index, float density_scale, int light_samples,
                          float resolution) {
  const ivec3 dims = glm::max(ivec3(glm::ceil(vec3(v.volume.dims) * resolution)), ivec3(2));
  Volume cache(dims, VoxelType::Float32);
  const vec3 extent = v.box.extent();
  cache.set_spacing(glm::max(extent / vec3(dims - 1), vec3(1e-6f)));
  cache.set_origin(v.box.lower);
  float* texels = cache.frame_as<float>(0);
  const VolumeView cache_view = cache.view();
  parallel_for(0, std::int64_t(dims.z) * dims.y, [&](std::int64_t first, std::int64_t last) {
    RayStats stats;
    for (std::int64_t row = first; row < last; ++row) {
      const int y = int(row % dims.y);
      const int z = int(row / dims.y);
      for (int x = 0; x < dims.x; ++x) {
        const vec3 p = cache_view.world_from_index(vec3(x, y, z));
        texels[x + std::int64_t(dims.x) * row] = light_transmittance(v, p, light_index, density_scale, light_samples, stats);
      }
    }
  });
  return cache;
}

}  // namespace penumbra

#pragma once
// The shadow cache of Ament et al. 2014, Algorithm 1: a float grid over the
// volume's world box holding one light's visibility per texel, so that
// rendering reads one trilinear sample instead of evaluating the tables per
// viewing-ray sample. Texel (0, 0, 0) sits on the box's lower corner and the
// last texel on its upper corner (the layout of shadow-rays' cache).
#include "penumbra/base/parallel.h"
#include "penumbra/volume/volume.h"

#include <cstdint>

namespace penumbra {

// Texels per axis for a volume of `data_dims` at `resolution` texels per
// voxel (at least 2 per axis).
ivec3 visibility_cache_dims(ivec3 data_dims, float resolution);

// A cache of `dims` texels over `box` with texel value visibility(world).
template <class Visibility> Volume build_visibility_cache(const Box3& box, ivec3 dims, const Visibility& visibility) {
  Volume cache(dims, VoxelType::Float32);
  cache.set_spacing(glm::max(box.extent() / vec3(dims - 1), vec3(1e-6f)));
  cache.set_origin(box.lower);
  float* texels = cache.frame_as<float>(0);
  const VolumeView view = cache.view();
  parallel_for(0, std::int64_t(dims.z) * dims.y, [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t row = first; row < last; ++row) {
      const int y = int(row % dims.y);
      const int z = int(row / dims.y);
      float* out = texels + std::int64_t(dims.x) * row;
      for (int x = 0; x < dims.x; ++x) out[x] = visibility(view.world_from_index(vec3(x, y, z)));
    }
  });
  return cache;
}

}  // namespace penumbra

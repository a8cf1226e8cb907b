#include "penumbra/techniques/sat_common/visibility_cache.h"

#include <algorithm>
#include <cmath>

namespace penumbra {

ivec3 visibility_cache_dims(ivec3 data_dims, float resolution) {
  return glm::max(ivec3(glm::ceil(vec3(data_dims) * resolution)), ivec3(2));
}

Volume unorm16_visibility(const Volume& cache) {
  Volume compact(cache.dims(), VoxelType::UInt16);
  compact.set_spacing(cache.spacing());
  compact.set_origin(cache.origin());
  const float* in = cache.frame_as<float>(0);
  std::uint16_t* out = compact.frame_as<std::uint16_t>(0);
  const ivec3 d = cache.dims();
  parallel_for(0, std::int64_t(d.x) * d.y * d.z, [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t i = first; i < last; ++i) {
      out[i] = std::uint16_t(std::lround(std::clamp(in[i], 0.0f, 1.0f) * 65535.0f));
    }
  });
  return compact;
}

}  // namespace penumbra

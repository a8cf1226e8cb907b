#include "penumbra/volume/normal_volume.h"

#include "penumbra/base/memory_budget.h"
#include "penumbra/base/parallel.h"

#include <fmt/format.h>

#include <cmath>

namespace penumbra {

NormalVolume::NormalVolume(const VolumeView& volume) : dims_(volume.dims) {
  const std::uint64_t voxels = std::uint64_t(dims_.x) * std::uint64_t(dims_.y) * std::uint64_t(dims_.z);
  check_memory_budget(fmt::format("shading normals for a {}x{}x{} volume", dims_.x, dims_.y, dims_.z), 4 * voxels);
  texels_.resize(4 * voxels);
  with_sampler(volume, [&](const auto& sampler) {
    // At voxel centres the central differences of the trilinear field are
    // differences of voxel values (one-sided at the border, as in
    // VolumeSampler::gradient).
    const auto* data = sampler.data;
    const std::int64_t stride[3] = {1, std::int64_t(dims_.x), std::int64_t(dims_.x) * dims_.y};
    parallel_for(0, std::int64_t(dims_.z) * dims_.y, [&](std::int64_t first, std::int64_t last) {
      for (std::int64_t row = first; row < last; ++row) {
        const int y = int(row % dims_.y);
        const int z = int(row / dims_.y);
        for (int x = 0; x < dims_.x; ++x) {
          const ivec3 i(x, y, z);
          const std::int64_t at = x + std::int64_t(dims_.x) * row;
          vec3 g(0.0f);
          for (int a = 0; a < 3; ++a) {
            const int lo = i[a] > 0 ? 1 : 0;
            const int hi = i[a] < dims_[a] - 1 ? 1 : 0;
            if (lo + hi == 0) continue;
            g[a] = (float(data[at + hi * stride[a]]) - float(data[at - lo * stride[a]])) / float(lo + hi);
          }
          g /= volume.spacing;
          const float len = glm::length(g);
          std::int8_t* t = &texels_[std::size_t(4 * at)];
          if (len > 0.0f && is_finite(len)) {
            const vec3 n = glm::round(g / len * 127.0f);
            t[0] = std::int8_t(n.x);
            t[1] = std::int8_t(n.y);
            t[2] = std::int8_t(n.z);
          } else {
            t[0] = t[1] = t[2] = 0;
          }
          t[3] = 0;
        }
      }
    });
    return 0;
  });
}

}  // namespace penumbra

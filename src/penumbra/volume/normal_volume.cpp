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
    parallel_for(0, std::int64_t(dims_.z) * dims_.y, [&](std::int64_t first, std::int64_t last) {
      for (std::int64_t row = first; row < last; ++row) {
        const int y = int(row % dims_.y);
        const int z = int(row / dims_.y);
        for (int x = 0; x < dims_.x; ++x) {
          // At voxel centres the trilinear gradient uses only voxel values.
          const vec3 g = sampler.gradient(vec3(x, y, z)) / volume.spacing;
          const float len = glm::length(g);
          std::int8_t* t = &texels_[std::size_t(4 * (x + std::int64_t(dims_.x) * row))];
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

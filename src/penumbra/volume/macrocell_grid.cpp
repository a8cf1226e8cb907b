#include "penumbra/volume/macrocell_grid.h"

#include "penumbra/base/error.h"
#include "penumbra/base/parallel.h"

#include <algorithm>
#include <limits>
#include <type_traits>

namespace penumbra {
namespace {

template <class T>
vec2 block_range(const T* data, ivec3 dims, ivec3 lo, ivec3 hi) {
  float mn = std::numeric_limits<float>::infinity();
  float mx = -std::numeric_limits<float>::infinity();
  for (int z = lo.z; z <= hi.z; ++z) {
    for (int y = lo.y; y <= hi.y; ++y) {
      const T* row = data + std::int64_t(dims.x) * (y + std::int64_t(dims.y) * z);
      if constexpr (std::is_floating_point_v<T>) {
        for (int x = lo.x; x <= hi.x; ++x) {
          const float v = static_cast<float>(row[x]);
          if (!is_finite(v)) continue;  // non-finite samples are transparent
          mn = std::min(mn, v);
          mx = std::max(mx, v);
        }
      } else {
        T row_min = row[lo.x], row_max = row[lo.x];
        for (int x = lo.x + 1; x <= hi.x; ++x) {
          row_min = std::min(row_min, row[x]);
          row_max = std::max(row_max, row[x]);
        }
        mn = std::min(mn, static_cast<float>(row_min));
        mx = std::max(mx, static_cast<float>(row_max));
      }
    }
  }
  return vec2(mn, mx);  // (inf, -inf) for a block without finite voxels: never opaque
}

}  // namespace

MacrocellGrid::MacrocellGrid(const VolumeView& volume, int cell_size) : cell_size_(cell_size) {
  if (cell_size < 1) throw InvalidArgument("cell_size", "macrocell size must be at least one voxel");
  const ivec3 cells = glm::max(volume.dims - 1, ivec3(1));
  dims_ = (cells + cell_size - 1) / cell_size;
  min_max_.resize(static_cast<std::size_t>(dims_.x) * dims_.y * dims_.z);
  const std::int64_t slices = dims_.z;
  parallel_for(0, slices, [&](std::int64_t z0, std::int64_t z1) {
    for (int cz = int(z0); cz < int(z1); ++cz) {
      for (int cy = 0; cy < dims_.y; ++cy) {
        for (int cx = 0; cx < dims_.x; ++cx) {
          const ivec3 c(cx, cy, cz);
          const ivec3 lo = glm::min(c * cell_size, volume.dims - 1);
          const ivec3 hi = glm::min((c + 1) * cell_size, volume.dims - 1);
          min_max_[static_cast<std::size_t>(view().index(c))] = visit_voxel_type(volume.type, [&](auto tag) {
            using T = decltype(tag);
            return block_range(static_cast<const T*>(volume.data), volume.dims, lo, hi);
          });
        }
      }
    }
  });
}

}  // namespace penumbra

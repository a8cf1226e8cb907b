#include "penumbra/volume/macrocell_grid.h"
#include "penumbra/volume/volume.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>

namespace penumbra {
namespace {

TEST(MacrocellGrid, RangesMatchBruteForceIncludingTheSharedBorderVoxels) {
  const ivec3 dims(19, 13, 10);
  Volume v(dims, VoxelType::UInt16);
  std::uint16_t* d = v.frame_as<std::uint16_t>(0);
  std::uint32_t state = 12345;
  for (std::uint64_t i = 0; i < v.voxel_count(); ++i) {
    state = state * 1664525u + 1013904223u;
    d[i] = std::uint16_t(state >> 20);
  }
  const MacrocellGrid grid(v.view(), 4);
  EXPECT_EQ(grid.dims(), ivec3(5, 3, 3));  // ceil((dims - 1) / 4)
  for (int cz = 0; cz < grid.dims().z; ++cz)
    for (int cy = 0; cy < grid.dims().y; ++cy)
      for (int cx = 0; cx < grid.dims().x; ++cx) {
        const ivec3 c(cx, cy, cz);
        float mn = std::numeric_limits<float>::infinity(), mx = -mn;
        const ivec3 lo = glm::min(c * 4, dims - 1), hi = glm::min((c + 1) * 4, dims - 1);
        for (int z = lo.z; z <= hi.z; ++z)
          for (int y = lo.y; y <= hi.y; ++y)
            for (int x = lo.x; x <= hi.x; ++x) {
              mn = std::min(mn, v.voxel(0, ivec3(x, y, z)));
              mx = std::max(mx, v.voxel(0, ivec3(x, y, z)));
            }
        EXPECT_EQ(grid.min_max(c), vec2(mn, mx)) << cx << "," << cy << "," << cz;
      }
}

}  // namespace
}  // namespace penumbra

#include "penumbra/render/majorant_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>

namespace penumbra {
namespace {

TEST(MajorantGrid, EmptySpaceDistanceIsTheChessboardDistanceToOccupiedCells) {
  const ivec3 dims(9, 7, 5);
  std::vector<float> majorant(std::size_t(dims.x * dims.y * dims.z), 0.0f);
  const std::vector<ivec3> occupied = {ivec3(1, 1, 1), ivec3(7, 5, 3), ivec3(4, 0, 4)};
  for (ivec3 c : occupied) majorant[std::size_t(c.x + dims.x * (c.y + dims.y * c.z))] = 1.0f;
  const auto d = empty_space_distance(majorant, dims);
  for (int z = 0; z < dims.z; ++z)
    for (int y = 0; y < dims.y; ++y)
      for (int x = 0; x < dims.x; ++x) {
        int expected = 1000;
        for (ivec3 c : occupied) {
          expected = std::min(expected, std::max({std::abs(x - c.x), std::abs(y - c.y), std::abs(z - c.z)}));
        }
        ASSERT_EQ(int(d[std::size_t(x + dims.x * (y + dims.y * z))]), expected) << x << "," << y << "," << z;
      }
}

TEST(MajorantGrid, AllEmptyGridsSaturate) {
  const auto d = empty_space_distance(std::vector<float>(8, 0.0f), ivec3(2));
  for (auto v : d) EXPECT_EQ(v, 255);
}

}  // namespace
}  // namespace penumbra

#include "server/volume_histogram.h"

#include "penumbra/base/error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numeric>

namespace penumbra::server {
namespace {

TEST(VolumeHistogram, EveryVoxelLandsInTheBinOfItsValue) {
  Volume v(ivec3(8, 6, 4), VoxelType::UInt8);
  for (int i = 0; i < 192; ++i) v.frame_as<std::uint8_t>(0)[i] = std::uint8_t(i);
  // 192 bins over [0, 192]: bin i covers [i, i + 1), so each holds one voxel.
  const VolumeHistogram h = volume_histogram(v, 0, vec2(0.0f, 192.0f), 192);
  ASSERT_EQ(h.counts.size(), 192u);
  for (std::uint64_t c : h.counts) EXPECT_EQ(c, 1u);
  EXPECT_EQ(h.below + h.above + h.non_finite, 0u);
}

TEST(VolumeHistogram, CountsWhatFallsOutsideTheRange) {
  Volume v(ivec3(8, 6, 4), VoxelType::UInt8);
  for (int i = 0; i < 192; ++i) v.frame_as<std::uint8_t>(0)[i] = std::uint8_t(i);
  const VolumeHistogram h = volume_histogram(v, 0, vec2(10.0f, 100.0f), 9);
  EXPECT_EQ(h.below, 10u);   // 0..9
  EXPECT_EQ(h.above, 91u);   // 101..191
  EXPECT_EQ(std::accumulate(h.counts.begin(), h.counts.end(), std::uint64_t(0)), 91u);
  EXPECT_EQ(h.counts.back(), 11u);  // [90, 100]: the top edge belongs to the last bin
}

TEST(VolumeHistogram, NonFiniteVoxelsAreCountedApart) {
  Volume v(ivec3(2, 2, 2), VoxelType::Float32);
  float* f = v.frame_as<float>(0);
  for (int i = 0; i < 8; ++i) f[i] = 0.25f;
  f[0] = std::numeric_limits<float>::quiet_NaN();
  f[1] = std::numeric_limits<float>::infinity();
  const VolumeHistogram h = volume_histogram(v, 0, vec2(0.0f, 1.0f), 4);
  EXPECT_EQ(h.non_finite, 2u);
  EXPECT_EQ(h.counts[1], 6u);
}

TEST(VolumeHistogram, ReadsTheRequestedTimeStep) {
  Volume v(ivec3(2, 2, 2), VoxelType::Float32, 2);
  for (int f = 0; f < 2; ++f) {
    for (int i = 0; i < 8; ++i) v.frame_as<float>(f)[i] = float(f) + 0.5f;
  }
  EXPECT_EQ(volume_histogram(v, 0, vec2(0.0f, 2.0f), 2).counts, (std::vector<std::uint64_t>{8, 0}));
  EXPECT_EQ(volume_histogram(v, 1, vec2(0.0f, 2.0f), 2).counts, (std::vector<std::uint64_t>{0, 8}));
}

TEST(VolumeHistogram, RejectsBadArguments) {
  Volume v(ivec3(2, 2, 2), VoxelType::UInt8);
  EXPECT_THROW(volume_histogram(v, 0, vec2(0.0f, 1.0f), 0), InvalidArgument);
  EXPECT_THROW(volume_histogram(v, 0, vec2(0.0f, 1.0f), 5000), InvalidArgument);
  EXPECT_THROW(volume_histogram(v, 0, vec2(1.0f, 1.0f), 4), InvalidArgument);
}

}  // namespace
}  // namespace penumbra::server

// The shadow caches' 16-bit storage (filtered-sat's, issue 22): the
// conversion keeps the geometry and rounds each texel to the nearest of
// 65535 steps, and LightVisibilityCaches keeps its caches in it once asked
// (rebuilding them when the storage changes).
#include "penumbra/techniques/sat_common/visibility_cache.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

namespace penumbra {
namespace {

float ramp(vec3 p) { return std::clamp(0.5f + 0.037f * p.x - 0.021f * p.y + 0.013f * p.z, 0.0f, 1.0f); }

TEST(VisibilityCache, Unorm16KeepsGeometryAndRoundsToTheNearestStep) {
  const Box3 box{vec3(-3.0f, 1.0f, 2.0f), vec3(9.0f, 6.0f, 11.0f)};
  Volume cache = build_visibility_cache(box, ivec3(7, 5, 9), ramp);
  float* v = cache.frame_as<float>(0);
  v[0] = -0.25f;  // out of [0, 1]: clamped
  v[1] = 1.5f;
  const Volume compact = unorm16_visibility(cache);
  ASSERT_EQ(compact.type(), VoxelType::UInt16);
  EXPECT_EQ(compact.dims(), cache.dims());
  EXPECT_EQ(compact.spacing(), cache.spacing());
  EXPECT_EQ(compact.origin(), cache.origin());
  const std::uint16_t* t = compact.frame_as<std::uint16_t>(0);
  EXPECT_EQ(t[0], 0);
  EXPECT_EQ(t[1], 65535);
  double worst = 0.0;
  for (int i = 2; i < 7 * 5 * 9; ++i) worst = std::max(worst, std::abs(double(t[i]) * kUnorm16Step - double(v[i])));
  EXPECT_LE(worst, 0.5 / 65535.0 + 1e-7);  // half a step: rounded, not truncated
  EXPECT_GT(worst, 0.2 / 65535.0);         // the ramp's values do fall between steps
}

TEST(VisibilityCache, CachesKeptIn16BitOnceAskedAndRebuiltWhenTheStorageChanges) {
  const Box3 box{vec3(0.0f), vec3(8.0f)};
  LightVisibilityCaches caches;
  const ParameterValues params;
  auto has = [](std::size_t) { return true; };
  auto stale = [](std::size_t) { return false; };
  auto visibility = [](std::size_t, vec3 p) { return ramp(p); };
  float seen_by_after_build = -1.0f;
  auto after = [&](std::size_t, const Volume& built) {
    ASSERT_EQ(built.type(), VoxelType::Float32) << "after_build sees the float cache";
    seen_by_after_build = built.frame_as<float>(0)[5];
  };
  EXPECT_EQ(caches.update(2, box, ivec3(5), params, has, stale, visibility, [](std::size_t) {}, after), 2);
  EXPECT_EQ(caches.views()[0].type, VoxelType::Float32);
  EXPECT_EQ(caches.update(2, box, ivec3(5), params, has, stale, visibility, [](std::size_t) {}, after), 0);
  caches.set_unorm16(true);
  EXPECT_EQ(caches.update(2, box, ivec3(5), params, has, stale, visibility, [](std::size_t) {}, after), 2);
  for (int i = 0; i < 2; ++i) {
    const VolumeView& v = caches.views()[i];
    ASSERT_EQ(v.type, VoxelType::UInt16);
    EXPECT_NEAR(v.voxel(ivec3(0, 1, 0)) * kUnorm16Step, seen_by_after_build, 0.5f / 65535.0f);
  }
  EXPECT_EQ(caches.bytes(), 2u * 5 * 5 * 5 * sizeof(std::uint16_t));
  EXPECT_EQ(caches.update(2, box, ivec3(5), params, has, stale, visibility, [](std::size_t) {}, after), 0);
}

}  // namespace
}  // namespace penumbra

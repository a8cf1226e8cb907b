#include "penumbra/base/error.h"
#include "penumbra/base/memory_budget.h"
#include "penumbra/volume/volume.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <vector>

namespace penumbra {
namespace {

// Fills a float volume with a + b.x * x + b.y * y + b.z * z in index space.
Volume linear_volume(ivec3 dims, vec3 b, float a) {
  Volume v(dims, VoxelType::Float32);
  float* d = v.frame_as<float>(0);
  for (int z = 0; z < dims.z; ++z)
    for (int y = 0; y < dims.y; ++y)
      for (int x = 0; x < dims.x; ++x) d[x + dims.x * (y + dims.y * z)] = a + b.x * x + b.y * y + b.z * z;
  return v;
}

TEST(Volume, RejectsBadDimensionsAndHugeSizes) {
  EXPECT_THROW(Volume(ivec3(0, 4, 4), VoxelType::UInt8), InvalidArgument);
  EXPECT_THROW(Volume(ivec3(-3, 4, 4), VoxelType::UInt8), InvalidArgument);
  EXPECT_THROW(Volume(ivec3(4), VoxelType::UInt8, 0), InvalidArgument);
  EXPECT_THROW(Volume(ivec3(1 << 20, 1 << 20, 1 << 20), VoxelType::Float64), OutOfMemoryBudget);
}

TEST(Volume, IsCentredAtTheOriginByDefault) {
  Volume v(ivec3(11, 21, 5), VoxelType::UInt8);
  v.set_spacing(vec3(0.5f, 1.0f, 2.0f));
  const Box3 box = v.world_box();
  EXPECT_FLOAT_EQ(box.lower.x, -2.5f);
  EXPECT_FLOAT_EQ(box.upper.x, 2.5f);
  EXPECT_FLOAT_EQ(box.lower.y, -10.0f);
  EXPECT_FLOAT_EQ(box.upper.z, 4.0f);
  v.set_origin(vec3(1.0f, 2.0f, 3.0f));
  EXPECT_FLOAT_EQ(v.world_box().lower.z, 3.0f);
  EXPECT_THROW(v.set_spacing(vec3(0.0f, 1.0f, 1.0f)), InvalidArgument);
}

// A finite spacing or origin can still put the box where its extent
// overflows a float; the box stays within 1e18 of the world origin.
TEST(Volume, TheBoxStaysWithinFloatRange) {
  Volume v(ivec3(8, 8, 6), VoxelType::UInt8);
  EXPECT_THROW(v.set_spacing(vec3(1.0f, 1.0f, 2.5e38f)), InvalidArgument);
  EXPECT_THROW(v.set_spacing(vec3(1e18f, 1.0f, 1.0f)), InvalidArgument);
  EXPECT_THROW(v.set_origin(vec3(0.0f, -3e38f, 0.0f)), InvalidArgument);
  EXPECT_EQ(v.spacing(), vec3(1.0f));  // unchanged by the refusals
  v.set_spacing(vec3(1e16f, 1.0f, 1.0f));
  EXPECT_FLOAT_EQ(v.world_box().upper.x, 3.5e16f);
}

TEST(Volume, ValueRangeSkipsNonFiniteVoxelsAndFollowsWrites) {
  Volume v(ivec3(4, 4, 4), VoxelType::Float32, 2);
  for (int f = 0; f < 2; ++f) {
    float* d = v.frame_as<float>(f);
    for (int i = 0; i < 64; ++i) d[i] = float(i + 100 * f);
  }
  v.frame_as<float>(0)[5] = std::numeric_limits<float>::quiet_NaN();
  v.frame_as<float>(0)[6] = std::numeric_limits<float>::infinity();
  EXPECT_FLOAT_EQ(v.value_range(0).min, 0.0f);
  EXPECT_FLOAT_EQ(v.value_range(0).max, 63.0f);
  EXPECT_EQ(v.value_range(0).non_finite, 2u);
  EXPECT_FLOAT_EQ(v.value_range(1).min, 100.0f);
  EXPECT_FLOAT_EQ(v.value_range().max, 163.0f);
  v.frame_as<float>(1)[0] = -7.0f;
  EXPECT_FLOAT_EQ(v.value_range().min, -7.0f);
  EXPECT_THROW(v.value_range(2), InvalidArgument);
}

TEST(Volume, FrameAccessChecksTheType) {
  Volume v(ivec3(2), VoxelType::Int16);
  EXPECT_NO_THROW(v.frame_as<std::int16_t>(0));
  EXPECT_THROW(v.frame_as<float>(0), InvalidArgument);
}


TEST(Volume, WrapReadsExternalFramesInPlaceAndKeepsTheirOwnerAlive) {
  // Two 3x2x2 int16 frames in one buffer, values = index + 1000 * frame.
  auto buffer = std::make_shared<std::vector<std::int16_t>>(24);
  for (int i = 0; i < 24; ++i) (*buffer)[std::size_t(i)] = std::int16_t(i % 12 + 1000 * (i / 12));
  std::weak_ptr<std::vector<std::int16_t>> alive = buffer;
  const auto* bytes = reinterpret_cast<const std::byte*>(buffer->data());
  auto v = std::make_shared<Volume>(Volume::wrap(ivec3(3, 2, 2), VoxelType::Int16, 2, bytes, buffer));
  buffer.reset();
  ASSERT_FALSE(alive.expired());  // the volume holds the owner
  EXPECT_TRUE(v->wraps_external_memory());
  EXPECT_EQ(v->frame_count(), 2);
  const Volume& read = *v;
  EXPECT_EQ(read.frame_data(1), read.frame_data(0) + 24);
  // No copy: the views read the wrapped bytes themselves.
  EXPECT_EQ(v->view(0).data, bytes);
  EXPECT_EQ(v->view(1).data, bytes + 24);
  EXPECT_FLOAT_EQ(v->voxel(1, ivec3(2, 1, 1)), 1011.0f);
  EXPECT_FLOAT_EQ(v->value_range().max, 1011.0f);
  EXPECT_FLOAT_EQ(v->world_box().center().x, 0.0f);
  // The owner writes; the volume forgets its cached range once told.
  alive.lock()->at(23) = 2000;
  EXPECT_FLOAT_EQ(v->value_range().max, 1011.0f);
  v->mark_modified();
  EXPECT_FLOAT_EQ(v->value_range().max, 2000.0f);
  EXPECT_THROW(v->frame_data(0), InvalidArgument);  // not writable through the volume
  v.reset();
  EXPECT_TRUE(alive.expired());
  EXPECT_THROW(Volume::wrap(ivec3(0, 2, 2), VoxelType::UInt8, 1, bytes, nullptr), InvalidArgument);
  EXPECT_THROW(Volume::wrap(ivec3(2), VoxelType::UInt8, 1, nullptr, nullptr), InvalidArgument);
}
TEST(VolumeView, TrilinearSamplingReproducesLinearFieldsAndVoxels) {
  const Volume v = linear_volume(ivec3(6, 7, 8), vec3(1.5f, -2.0f, 0.25f), 3.0f);
  const VolumeView view = v.view();
  EXPECT_FLOAT_EQ(view.voxel(ivec3(2, 3, 4)), 3.0f + 3.0f - 6.0f + 1.0f);
  for (vec3 p : {vec3(0.0f), vec3(2.3f, 4.7f, 1.1f), vec3(5.0f, 6.0f, 7.0f), vec3(4.99f, 0.01f, 6.5f)}) {
    EXPECT_NEAR(view.sample_index(p), 3.0f + 1.5f * p.x - 2.0f * p.y + 0.25f * p.z, 1e-4f);
  }
  // Outside the grid, samples clamp to the border.
  EXPECT_NEAR(view.sample_index(vec3(-3.0f, 0.0f, 0.0f)), 3.0f, 1e-5f);
}

TEST(VolumeView, GradientOfALinearFieldIsExactInWorldUnits) {
  Volume v = linear_volume(ivec3(9, 9, 9), vec3(2.0f, -1.0f, 0.5f), 1.0f);
  v.set_spacing(vec3(0.5f, 2.0f, 1.0f));
  const VolumeView view = v.view();
  // Interior and border positions (one-sided differences at the border).
  for (vec3 p : {vec3(4.2f, 3.3f, 5.9f), vec3(0.0f, 0.0f, 0.0f), vec3(8.0f, 7.5f, 8.0f)}) {
    const vec3 g = view.gradient_index(p);
    EXPECT_NEAR(g.x, 2.0f / 0.5f, 1e-4f);
    EXPECT_NEAR(g.y, -1.0f / 2.0f, 1e-4f);
    EXPECT_NEAR(g.z, 0.5f / 1.0f, 1e-4f);
  }
  // World-space sampling agrees with index space.
  const vec3 world = view.world_from_index(vec3(1.0f, 2.0f, 3.0f));
  EXPECT_NEAR(view.sample(world), 1.0f + 2.0f - 2.0f + 1.5f, 1e-4f);
}

TEST(VolumeView, EveryVoxelTypeSamples) {
  for (VoxelType t : {VoxelType::UInt8, VoxelType::Int8, VoxelType::UInt16, VoxelType::Int16, VoxelType::UInt32,
                      VoxelType::Int32, VoxelType::Float32, VoxelType::Float64}) {
    Volume v(ivec3(2, 2, 2), t);
    visit_voxel_type(t, [&](auto tag) {
      using T = decltype(tag);
      T* d = reinterpret_cast<T*>(v.frame_data(0));
      for (int i = 0; i < 8; ++i) d[i] = T(i * 10);
      return 0;
    });
    EXPECT_NEAR(v.view().sample_index(vec3(0.5f)), 35.0f, 1e-4f) << to_string(t);
    EXPECT_EQ(voxel_type_from_string(to_string(t)), t);
  }
}

TEST(VolumeView, SingleVoxelThickAxesDoNotReadOutOfBounds) {
  Volume v(ivec3(3, 3, 1), VoxelType::UInt8);
  std::uint8_t* d = v.frame_as<std::uint8_t>(0);
  for (int i = 0; i < 9; ++i) d[i] = std::uint8_t(i);
  EXPECT_NEAR(v.view().sample_index(vec3(1.5f, 1.0f, 0.0f)), 4.5f, 1e-5f);
  EXPECT_NEAR(v.view().gradient_index(vec3(1.0f, 1.0f, 0.0f)).z, 0.0f, 1e-6f);
}

}  // namespace
}  // namespace penumbra

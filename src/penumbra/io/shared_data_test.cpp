// Every real volume in ../shared/data reads with the dimensions, type,
// spacing and value range its README states.
#include "penumbra/io/io_test_support.h"
#include "penumbra/io/volume_reader.h"

#include <gtest/gtest.h>

#include <numeric>

namespace penumbra {
namespace {

class IoSharedData : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!std::filesystem::is_directory(test::shared_data_dir())) {
      GTEST_SKIP() << "shared data folder " << test::shared_data_dir() << " is absent";
    }
  }
  static std::shared_ptr<Volume> read(const std::string& name) {
    const auto volume = read_volume(test::shared_data_dir() / name);
    EXPECT_EQ(volume->source(), (test::shared_data_dir() / name).string());
    return volume;
  }
};

TEST_F(IoSharedData, EngineIsGzipNrrdWithFullByteRange) {
  const auto v = read("engine_256x256x128_uint8.nhdr");
  EXPECT_EQ(v->dims(), ivec3(256, 256, 128));
  EXPECT_EQ(v->type(), VoxelType::UInt8);
  EXPECT_EQ(v->spacing(), vec3(1.0f));
  EXPECT_EQ(v->value_range().min, 0.0f);
  EXPECT_EQ(v->value_range().max, 255.0f);
  // No origin in the header: centred.
  EXPECT_EQ(v->world_box().lower, vec3(-127.5f, -127.5f, -63.5f));
}

TEST_F(IoSharedData, CraniumIsInt16HounsfieldUnitsWithAnisotropicSpacing) {
  const auto v = read("ct_head_cranium_256x256x108_int16.nhdr");
  EXPECT_EQ(v->dims(), ivec3(256, 256, 108));
  EXPECT_EQ(v->type(), VoxelType::Int16);
  EXPECT_NEAR(v->spacing().x, 0.957f, 1e-3f);
  EXPECT_NEAR(v->spacing().y, 0.957f, 1e-3f);
  EXPECT_FLOAT_EQ(v->spacing().z, 1.5f);
  EXPECT_EQ(v->value_range().min, -1024.0f);
  EXPECT_EQ(v->value_range().max, 2986.0f);
}

TEST_F(IoSharedData, ColinMriIsGzipNiftiAtOneMillimetre) {
  const auto v = read("mri_ch2_colin27_181x217x181_uint8.nii.gz");
  EXPECT_EQ(v->dims(), ivec3(181, 217, 181));
  EXPECT_EQ(v->type(), VoxelType::UInt8);
  EXPECT_EQ(v->spacing(), vec3(1.0f));
  EXPECT_EQ(v->value_range().min, 0.0f);
  EXPECT_GT(v->value_range().max, 200.0f);
  // Its sform is an axis-aligned MNI placement.
  EXPECT_EQ(v->origin(), vec3(-90.0f, -125.0f, -71.0f));
}

TEST_F(IoSharedData, SmallVolumesHaveTheirStatedDimensions) {
  struct Case {
    const char* file;
    ivec3 dims;
  };
  for (const Case& c : {Case{"mri_brainsmall_128x128x84_uint8.nhdr", ivec3(128, 128, 84)},
                        Case{"tooth_103x94x161_uint8.nrrd", ivec3(103, 94, 161)},
                        Case{"nucleon_41x41x41_uint8.nhdr", ivec3(41)},
                        Case{"bucky_32x32x32_uint8.nhdr", ivec3(32)}}) {
    SCOPED_TRACE(c.file);
    const auto v = read(c.file);
    EXPECT_EQ(v->dims(), c.dims);
    EXPECT_EQ(v->type(), VoxelType::UInt8);
    EXPECT_EQ(v->frame_count(), 1);
    EXPECT_EQ(v->spacing(), vec3(1.0f));
    EXPECT_LT(v->value_range().min, v->value_range().max);
  }
  // The tooth's header gives space directions and an origin of (0,0,0).
  EXPECT_EQ(read("tooth_103x94x161_uint8.nrrd")->origin(), vec3(0.0f));
}

TEST_F(IoSharedData, ViscousFingersSeriesHasTenFramesWhoseMeanRises) {
  const auto v = read("viscous_fingers/series.nhdr");
  EXPECT_EQ(v->dims(), ivec3(64));
  EXPECT_EQ(v->type(), VoxelType::Float32);
  ASSERT_EQ(v->frame_count(), 10);
  double previous = -1.0;
  for (int f = 0; f < v->frame_count(); ++f) {
    const float* data = v->frame_as<float>(f);
    const double mean = std::accumulate(data, data + v->voxel_count(), 0.0) / double(v->voxel_count());
    EXPECT_GT(mean, previous) << "frame " << f;
    previous = mean;
    EXPECT_EQ(v->value_range(f).non_finite, 0u);
  }
}

}  // namespace
}  // namespace penumbra

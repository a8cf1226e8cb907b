#include "penumbra/base/error.h"
#include "penumbra/volume/procedural.h"

#include <gtest/gtest.h>

namespace penumbra {
namespace {

TEST(Procedural, EveryGeneratorBuildsAVolumeInTheUnitRange) {
  for (const ProceduralInfo& info : procedural_volumes()) {
    const auto v = make_procedural_volume(info.name, ivec3(17, 15, 13));
    EXPECT_EQ(v->dims(), ivec3(17, 15, 13)) << info.name;
    EXPECT_GE(v->value_range().min, 0.0f) << info.name;
    EXPECT_LE(v->value_range().max, 1.0f) << info.name;
    if (info.name == "empty") {
      EXPECT_EQ(v->value_range().max, 0.0f);
    } else {
      EXPECT_GT(v->value_range().max, 0.0f) << info.name;
    }
  }
}

TEST(Procedural, VoxelsHoldTheAnalyticField) {
  const auto v = make_procedural_volume("spheres", ivec3(33));
  // Voxel 16 is the centre p = 0; a voxel near sphere 0's centre is close to 1.
  const vec3 p = kSpheres[0].center;
  const ivec3 i = ivec3(glm::round((p + 1.0f) * 16.0f));
  const vec3 snapped = vec3(i) / 16.0f - 1.0f;
  EXPECT_FLOAT_EQ(v->voxel(0, i), procedural_value("spheres", snapped, ivec3(33)));
  EXPECT_GT(v->voxel(0, i), 0.8f);
  EXPECT_FLOAT_EQ(procedural_value("shell", vec3(0.0f), ivec3(33)), 1.0f);
  EXPECT_FLOAT_EQ(procedural_value("shell", vec3(0.7f, 0.0f, 0.0f), ivec3(33)), 0.5f);
}

TEST(Procedural, RejectsUnknownNamesAndTinySizes) {
  EXPECT_THROW(make_procedural_volume("teapot", ivec3(8)), InvalidArgument);
  EXPECT_THROW(make_procedural_volume("spheres", ivec3(1, 8, 8)), InvalidArgument);
}

}  // namespace
}  // namespace penumbra

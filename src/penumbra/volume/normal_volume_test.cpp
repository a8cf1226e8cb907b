#include "penumbra/volume/normal_volume.h"
#include "penumbra/volume/volume.h"

#include <gtest/gtest.h>

#include <cmath>

namespace penumbra {
namespace {

TEST(NormalVolume, MatchesTheExactGradientDirectionWithinQuantisation) {
  // A smooth radial field with anisotropic spacing.
  const ivec3 dims(24, 20, 16);
  Volume v(dims, VoxelType::Float32);
  v.set_spacing(vec3(1.0f, 1.5f, 2.0f));
  float* d = v.frame_as<float>(0);
  for (int z = 0; z < dims.z; ++z)
    for (int y = 0; y < dims.y; ++y)
      for (int x = 0; x < dims.x; ++x) {
        const vec3 p = v.view().world_from_index(vec3(x, y, z));
        d[x + dims.x * (y + dims.y * z)] = std::exp(-glm::dot(p, p) / 200.0f);
      }
  const NormalVolume normals(v.view());
  EXPECT_EQ(normals.bytes(), 4u * 24u * 20u * 16u);
  double worst_deg = 0.0;
  for (vec3 p : {vec3(5.0f, 6.0f, 3.0f), vec3(17.5f, 4.25f, 11.0f), vec3(3.0f, 15.0f, 12.5f)}) {
    const vec3 exact = glm::normalize(v.view().gradient_index(p));
    const vec3 stored = glm::normalize(normals.view().sample(p));
    worst_deg = std::max(worst_deg, double(glm::degrees(std::acos(glm::min(1.0f, glm::dot(exact, stored))))));
  }
  // At voxel centres only quantisation (< 0.5 deg); between them the
  // interpolated direction of a smooth field stays within a few degrees.
  EXPECT_LT(worst_deg, 3.0);
  const vec3 at_voxel = glm::normalize(normals.view().sample(vec3(5.0f, 6.0f, 3.0f)));
  const vec3 exact = glm::normalize(v.view().gradient_index(vec3(5.0f, 6.0f, 3.0f)));
  EXPECT_LT(glm::degrees(std::acos(glm::min(1.0f, glm::dot(at_voxel, exact)))), 0.8f);
}

TEST(NormalVolume, HomogeneousRegionsHaveNoNormal) {
  Volume v(ivec3(8), VoxelType::UInt8);
  std::fill_n(v.frame_as<std::uint8_t>(0), 512, std::uint8_t(7));
  const NormalVolume normals(v.view());
  EXPECT_EQ(normals.view().sample(vec3(3.5f)), vec3(0.0f));
}

}  // namespace
}  // namespace penumbra

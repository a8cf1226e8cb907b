#include "penumbra/scene/detail_view.h"

#include "penumbra/base/error.h"
#include "penumbra/base/rng.h"

#include <gtest/gtest.h>

#include <limits>
#include <memory>
#include <utility>

namespace penumbra {
namespace {

DetailFunction noise_detail(DetailType type, bool time_dependent) {
  DetailFunction d;
  d.type = type;
  d.frequency = 3.0f;
  d.fractal.octaves = 4;
  d.fractal.lacunarity = 2.2f;
  d.fractal.gain = 0.45f;
  d.fractal.offset = 0.95f;
  d.fractal.time = 1.4f;
  d.time_dependent = time_dependent;
  d.seed = 12;
  return d;
}

const Box3 kBounds{vec3(-1.0f, 0.0f, 2.0f), vec3(1.0f, 3.0f, 4.0f)};

TEST(ConvolutionDetailView, ConstantIsTheValue) {
  DetailFunction d;
  d.type = DetailType::Constant;
  d.value = 0.625f;
  const DetailResources resources(d, kBounds);
  EXPECT_EQ(resources.view()(vec3(0.3f, -8.0f, 2.0f)), 0.625f);
}

TEST(ConvolutionDetailView, NoiseTypesEvaluateTheirFunctions) {
  const NoiseTable table = make_noise_table(12);
  Pcg32 rng(3);
  for (bool time_dependent : {false, true}) {
    for (DetailType type : {DetailType::Noise, DetailType::Fbm, DetailType::Ridged}) {
      const DetailFunction d = noise_detail(type, time_dependent);
      const DetailResources resources(d, kBounds);
      const DetailView view = resources.view();
      for (int i = 0; i < 50; ++i) {
        const vec3 p(rng.next_float() * 2.0f - 1.0f, rng.next_float() * 3.0f, rng.next_float() * 2.0f + 2.0f);
        const vec3 q = 3.0f * p;
        const vec4 q4(q, 1.4f);
        float want = 0.0f;
        if (type == DetailType::Noise)
          want = time_dependent ? improved_noise(table, q4) : improved_noise(table, q);
        else if (type == DetailType::Fbm)
          want = time_dependent ? fbm(table, q4, d.fractal) : fbm(table, q, d.fractal);
        else
          want = time_dependent ? ridged_multifractal(table, q4, d.fractal) : ridged_multifractal(table, q, d.fractal);
        EXPECT_NEAR(view(p), want, 1e-6f);  // the same operations; 1e-6 allows FMA contraction
      }
    }
  }
  // Time dependence shows: the same point at another time differs.
  DetailFunction d = noise_detail(DetailType::Fbm, true);
  const float before = DetailResources(d, kBounds).view()(vec3(0.31f, 1.17f, 2.53f));
  d.fractal.time = 2.1f;
  EXPECT_NE(DetailResources(d, kBounds).view()(vec3(0.31f, 1.17f, 2.53f)), before);
}

TEST(ConvolutionDetailView, TextureReproducesVoxelsAtTheirCentres) {
  auto volume = std::make_shared<Volume>(ivec3(3, 4, 5), VoxelType::Float32);
  float* voxels = volume->frame_as<float>(0);
  for (int i = 0; i < 3 * 4 * 5; ++i) voxels[i] = float((i * 37) % 11) - 3.5f;
  DetailFunction d;
  d.type = DetailType::Texture;
  d.texture = volume;
  d.texture_file = "test.nrrd";
  DetailResources resources(d, kBounds);
  const DetailResources moved = std::move(resources);  // the view is rebuilt from the moved object
  const DetailView view = moved.view();
  const vec3 extent = kBounds.extent();
  for (int z = 0; z < 5; ++z)
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 3; ++x) {
        const vec3 p = kBounds.lower + vec3(x / 2.0f, y / 3.0f, z / 4.0f) * extent;
        // Index rounding of a few ulps times a neighbour difference of <= 10.
        EXPECT_NEAR(view(p), volume->voxel(0, ivec3(x, y, z)), 1e-4f) << x << " " << y << " " << z;
      }
  // Halfway between two centres along x: their mean (trilinear).
  const vec3 mid = kBounds.lower + vec3(0.25f, 1.0f / 3.0f, 0.5f) * extent;
  EXPECT_NEAR(view(mid), 0.5f * (volume->voxel(0, ivec3(0, 1, 2)) + volume->voxel(0, ivec3(1, 1, 2))), 1e-4f);
  // Outside the bounds: clamped to the border voxels.
  EXPECT_NEAR(view(kBounds.upper + vec3(5.0f)), volume->voxel(0, ivec3(2, 3, 4)), 1e-6f);
  // Flat bounds along z read the first slice.
  const DetailResources flat(d, Box3{vec3(-1.0f, 0.0f, 2.0f), vec3(1.0f, 3.0f, 2.0f)});
  EXPECT_NEAR(flat.view()(vec3(1.0f, 3.0f, 2.0f)), volume->voxel(0, ivec3(2, 3, 0)), 1e-6f);
}

TEST(ConvolutionDetailView, RejectsMissingTextureAndBadParameters) {
  DetailFunction d;
  d.type = DetailType::Texture;
  d.texture_file = "missing.nrrd";
  try {
    DetailResources resources(d, kBounds);
    FAIL() << "expected InvalidArgument";
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.name(), "detail.texture");
  }
  DetailFunction bad = noise_detail(DetailType::Fbm, false);
  bad.fractal.octaves = 100;
  EXPECT_THROW(DetailResources(bad, kBounds), InvalidArgument);
  bad = noise_detail(DetailType::Fbm, false);
  bad.frequency = std::numeric_limits<float>::infinity();
  EXPECT_THROW(DetailResources(bad, kBounds), InvalidArgument);
}

}  // namespace
}  // namespace penumbra

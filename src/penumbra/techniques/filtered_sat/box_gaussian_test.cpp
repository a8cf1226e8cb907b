// Ament et al. 2014, Fig. 6: on real data the box filter looks like the
// Gaussian of comparable width, because little of the shadows' energy sits
// at the frequencies where the sinc oscillates. Measured as in the paper: the
// CIELAB lightness difference L* (0..100) between the two images.
#include "penumbra/analysis/color_space.h"
#include "penumbra/io/scene_json.h"
#include "test_scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

namespace penumbra {
namespace {

TEST(FilteredSatOnRealData, BoxAndGaussianOfComparableWidthLookAlikeOnTheEngine) {
  const std::filesystem::path scene_file = std::filesystem::path(PENUMBRA_SOURCE_DIR) / "scenes" / "engine.json";
  if (!std::filesystem::exists(std::filesystem::path(PENUMBRA_SHARED_DATA_DIR) / "engine_256x256x128_uint8.nhdr")) {
    GTEST_SKIP() << "the engine CT is not in " << PENUMBRA_SHARED_DATA_DIR;
  }
  Scene scene = load_scene(scene_file);
  RenderSettings r = scene.render();
  r.width = r.height = 64;
  scene.set_render(r);
  // The volume alone, as in the paper's figure (no floor: a floor far below
  // an oblique light shows penumbrae many filter widths wide, where the
  // kernels' different supports, +-3 sigma = +-7.8 voxels against the box's
  // +-4.5, separate the two most).
  scene.set_planes({});
  const ParameterSettings box = {{"filter_voxels", 9.0}, {"sat_resolution", 0.5}, {"cache_resolution", 0.25}};
  ParameterSettings gaussian = box;
  gaussian["kernel"] = std::string("gaussian");
  const Image a = testing::render_with(scene, "filtered-sat", box);
  const Image b = testing::render_with(scene, "filtered-sat", gaussian);
  const Image hard = testing::render_with(scene, "shadow-rays");
  std::vector<double> differences;
  double sum = 0.0, sum_hard = 0.0;
  for (std::size_t i = 0; i < a.pixel_count(); ++i) {
    auto lightness = [&](const Image& image) {
      return srgb_linear_to_lab(glm::clamp(vec3(image.data()[i]), vec3(0.0f), vec3(1.0f))).l;
    };
    differences.push_back(std::abs(lightness(a) - lightness(b)));
    sum += differences.back();
    sum_hard += std::abs(lightness(a) - lightness(hard));
  }
  std::sort(differences.begin(), differences.end());
  const double mean = sum / double(a.pixel_count());
  const double p99 = differences[differences.size() * 99 / 100];
  std::printf("box vs gaussian |dL*|: mean %.3f, 99th percentile %.3f, max %.3f; box vs hard shadows: mean %.3f\n",
              mean, p99, differences.back(), sum_hard / double(a.pixel_count()));
  // "Well under 2% of the range": the mean under 0.5 L* (a quarter of 2%)
  // and 99% of the pixels under 2 L*. The filter itself matters: against
  // hard shadows the mean difference is far larger.
  EXPECT_LT(mean, 0.5);
  EXPECT_LT(p99, 2.0);
  EXPECT_GT(sum_hard / double(a.pixel_count()), 5.0 * mean);
}

}  // namespace
}  // namespace penumbra

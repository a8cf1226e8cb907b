// Patel et al. 2013, Fig. 14: a thin occluder above a parallel plane lit by
// three Gaussian lights, a green one of low isotropic spread, a red one of
// four times its variance, and a blue one spread along one axis only, turned
// 70 degrees clockwise (scenes/fig14-plate-over-plane.json).
//
// The paper gives variances on its own virtual light plane (0.8, 3.2 and a
// "high" one) in units we cannot recover; the scene keeps their 1 : 4 ratio
// in tan^2 units on our unit-distance plane: green tan^2 = 0.01 (5.71 deg),
// red 0.04 (11.31 deg), blue tan^2 = 0 along x and 0.09 (16.7 deg) along y,
// rotation_deg -70 (negative = clockwise seen from the light, which for this
// camera looking down with up +y is clockwise in the image). With the plate
// about 19-21 units above the floor that blurs the shadows by standard
// deviations of about 2, 4 and 6 units against an 8-unit plate: visibly soft,
// and the blue one a streak 20 degrees above the image's x axis.
//
// The convolution technique's soft shadows should match
// the path tracer's far better than hard shadow rays do, and the blue
// shadow's orientation should be the path tracer's: the same light turned the
// other way (+70 degrees) must match it worse. At 48^2 (issue 23; at 32^2
// d1 = 5 / 20 / 80 gave 1.12 / 1.27 / 1.54, all under the bound) the best fit
// is at the plate's geometric distance d1 = 20 and halving or doubling the
// variance (d1 = 10 or 40) is visibly worse: mean dE measured 1.23 / 1.06 /
// 0.95 / 1.10 / 1.36 for d1 = 5 / 10 / 20 / 40 / 80.
#include "penumbra/analysis/image_metrics.h"
#include "penumbra/io/scene_json.h"
#include "penumbra/techniques/registry.h"
#include "test_scene.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

namespace penumbra {
namespace {

using testing::render_with;

TEST(Convolution, Fig14AnisotropicLightsApproachPathtrace) {
  Scene scene = testing::repository_scene("scenes/fig14-plate-over-plane.json", 48);
  const Image reference = render_with(scene, "pathtrace", {{"spp", 1024.0}, {"progress", false}});
  const ParameterSettings params{{"slab_distance", 0.5}, {"optimal_distance", 20.0}};
  const Image conv_image = render_with(scene, "convolution", params);
  const double conv = delta_e_stats(conv_image, reference).mean;
  const double rays = delta_e_stats(render_with(scene, "shadow-rays"), reference).mean;
  // A variance error of 2x either way: d1 scales the per-slab kernel's variance.
  double off_by_two[2];
  for (int i = 0; i < 2; ++i) {
    const ParameterSettings off{{"slab_distance", 0.5}, {"optimal_distance", i == 0 ? 10.0 : 40.0}};
    off_by_two[i] = delta_e_stats(render_with(scene, "convolution", off), reference).mean;
  }
  std::vector<Light> lights = scene.lights();
  ASSERT_EQ(lights.size(), 3u);
  ASSERT_EQ(lights[2].rotation_deg, -70.0f);
  lights[2].rotation_deg = 70.0f;  // the blue light mirrored
  Scene mirrored = scene;
  mirrored.set_lights(lights);
  const Image wrong_image = render_with(mirrored, "convolution", params);
  // Judge the orientation where it shows: on the pixels where the two
  // orientations differ visibly (dE > 1 between them: the blue shadow).
  const std::vector<float> between = delta_e_2000_per_pixel(wrong_image, conv_image);
  const std::vector<float> right = delta_e_2000_per_pixel(conv_image, reference);
  const std::vector<float> wrong = delta_e_2000_per_pixel(wrong_image, reference);
  double right_sum = 0.0, wrong_sum = 0.0;
  int count = 0;
  for (std::size_t i = 0; i < between.size(); ++i) {
    if (!(between[i] > 1.0f)) continue;
    right_sum += right[i], wrong_sum += wrong[i], ++count;
  }
  ASSERT_GT(count, 20);  // the orientation changes a visible part of the image
  testing::save_test_image(reference, "fig14_pathtrace.png");
  testing::save_test_image(conv_image, "fig14_convolution.png");
  std::printf("fig14 (48^2): mean dE convolution %.3f (d1 10: %.3f, d1 40: %.3f), shadow-rays %.2f; on the %d "
              "pixels the blue light's orientation changes: %.2f at -70 deg, %.2f mirrored to +70 deg\n",
              conv, off_by_two[0], off_by_two[1], rays, count, right_sum / count, wrong_sum / count);
  // Observed 0.95 (1.27 at 32^2 before the kernels' interpolation
  // correction); 1.2 leaves ~25% for floating-point and noise differences
  // across platforms. A 2x variance error costs 0.11 / 0.16 here: 0.05 is
  // about half of the smaller.
  EXPECT_LT(conv, 1.2);
  EXPECT_GT(off_by_two[0], conv + 0.05);
  EXPECT_GT(off_by_two[1], conv + 0.05);
  EXPECT_LT(conv, rays);
  // Observed 1.30 against 2.35 (ratio 0.55); 0.7 still fails a mirrored or
  // ignored rotation, which gives a ratio near or above 1.
  EXPECT_LT(right_sum, 0.7 * wrong_sum);
}

}  // namespace
}  // namespace penumbra

#include "penumbra/analysis/color_map.h"

#include "penumbra/analysis/color_space.h"

#include <gtest/gtest.h>

#include <cmath>

namespace penumbra {
namespace {

TEST(ColorMap, ViridisEndsAtItsPublishedAnchorsAndClamps) {
  const vec3 first = srgb_encode(map_color(ColorMap::viridis, 0.0f)) * 255.0f;
  const vec3 last = srgb_encode(map_color(ColorMap::viridis, 1.0f)) * 255.0f;
  EXPECT_NEAR(first.r, 68.0f, 0.01f);  // #440154
  EXPECT_NEAR(first.g, 1.0f, 0.01f);
  EXPECT_NEAR(first.b, 84.0f, 0.01f);
  EXPECT_NEAR(last.r, 253.0f, 0.01f);  // #fde725
  EXPECT_NEAR(last.g, 231.0f, 0.01f);
  EXPECT_NEAR(last.b, 37.0f, 0.01f);
  EXPECT_EQ(map_color(ColorMap::viridis, -3.0f), map_color(ColorMap::viridis, 0.0f));
  EXPECT_EQ(map_color(ColorMap::viridis, 7.0f), map_color(ColorMap::viridis, 1.0f));
}

TEST(ColorMap, ViridisLightnessIncreasesMonotonically) {
  double previous = -1.0;
  for (int i = 0; i <= 256; ++i) {
    const double lightness = srgb_linear_to_lab(map_color(ColorMap::viridis, float(i) / 256.0f)).l;
    EXPECT_GT(lightness, previous) << i;
    previous = lightness;
  }
}

TEST(ColorMap, CoolWarmIsNeutralInTheMiddleAndLighterThanItsEnds) {
  const Lab middle = srgb_linear_to_lab(map_color(ColorMap::cool_warm, 0.5f));
  EXPECT_NEAR(middle.a, 0.0, 1e-6);
  EXPECT_NEAR(middle.b, 0.0, 1e-6);
  const vec3 cool = map_color(ColorMap::cool_warm, 0.0f);
  const vec3 warm = map_color(ColorMap::cool_warm, 1.0f);
  EXPECT_GT(cool.b, cool.r);
  EXPECT_GT(warm.r, warm.b);
  EXPECT_LT(srgb_linear_to_lab(cool).l, middle.l);
  EXPECT_LT(srgb_linear_to_lab(warm).l, middle.l);
}

TEST(ColorMap, NaNIsMagenta) {
  EXPECT_EQ(map_color(ColorMap::viridis, std::nanf("")), vec3(1.0f, 0.0f, 1.0f));
}

}  // namespace
}  // namespace penumbra

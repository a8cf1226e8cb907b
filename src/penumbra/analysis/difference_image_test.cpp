#include "penumbra/analysis/difference_image.h"

#include "penumbra/analysis/color_map.h"
#include "penumbra/analysis/image_metrics.h"
#include "penumbra/analysis/label_style.h"
#include "penumbra/base/error.h"

#include <gtest/gtest.h>

namespace penumbra {
namespace {

void expect_rgb_near(vec4 actual, vec3 expected, float tolerance) {
  EXPECT_NEAR(actual.r, expected.r, tolerance);
  EXPECT_NEAR(actual.g, expected.g, tolerance);
  EXPECT_NEAR(actual.b, expected.b, tolerance);
}

TEST(DifferenceImage, MapsZeroToTheFirstColourAndSaturatesAtTheScale) {
  const Image reference(24, 16, vec4(0.3f, 0.3f, 0.3f, 1.0f));
  Image test = reference;
  test.at(5, 5) = vec4(0.9f, 0.1f, 0.1f, 1.0f);   // far above 10 dE
  test.at(6, 5) = vec4(0.31f, 0.3f, 0.3f, 1.0f);  // a small difference
  const Image diff = make_delta_e_image(test, reference, 10.0f);

  expect_rgb_near(diff.at(0, 0), map_color(ColorMap::viridis, 0.0f), 0.0f);
  expect_rgb_near(diff.at(23, 15), map_color(ColorMap::viridis, 0.0f), 0.0f);
  expect_rgb_near(diff.at(5, 5), map_color(ColorMap::viridis, 1.0f), 0.0f);
  const float small = delta_e_2000_per_pixel(test, reference)[5 * 24 + 6];
  ASSERT_GT(small, 0.0f);
  ASSERT_LT(small, 10.0f);
  expect_rgb_near(diff.at(6, 5), map_color(ColorMap::viridis, small / 10.0f), 1e-6f);
  EXPECT_EQ(diff.at(0, 0).a, 1.0f);
}

TEST(DifferenceImage, HasALabelledColourBarOnTheRight) {
  const Image reference(50, 120, vec4(0.5f, 0.4f, 0.3f, 1.0f));
  const Image diff = make_delta_e_image(reference, reference, 5.0f);
  const ColorBarLayout layout = color_bar_layout(50, 120, ColorBar{ColorMap::viridis, 0.0f, 5.0f, "dE2000"});
  EXPECT_EQ(diff.width(), layout.width);
  EXPECT_EQ(diff.height(), 120);
  EXPECT_GT(diff.width(), 50 + layout.bar_x1 - layout.bar_x0);
  EXPECT_GE(layout.bar_x0, 50);
  EXPECT_EQ(layout.tick_count, 5);

  // The bar runs from the map's first colour at the bottom to its last at the top.
  const int mid_x = (layout.bar_x0 + layout.bar_x1) / 2;
  expect_rgb_near(diff.at(mid_x, layout.bar_bottom - 1), map_color(ColorMap::viridis, 0.0f), 1e-6f);
  expect_rgb_near(diff.at(mid_x, layout.bar_top), map_color(ColorMap::viridis, 1.0f), 1e-6f);

  // Tick marks at both ends, left of the bar.
  EXPECT_EQ(vec3(diff.at(layout.bar_x0 - 1, layout.bar_bottom - 1)), kLabelText);
  EXPECT_EQ(vec3(diff.at(layout.bar_x0 - 1, layout.bar_top)), kLabelText);

  // Tick labels: text-coloured pixels right of the bar, background elsewhere in the strip.
  int text_pixels = 0;
  for (int y = 0; y < diff.height(); ++y) {
    for (int x = layout.bar_x1; x < diff.width(); ++x) {
      text_pixels += vec3(diff.at(x, y)) == kLabelText ? 1 : 0;
    }
  }
  EXPECT_GT(text_pixels, 40);
  EXPECT_EQ(vec3(diff.at(diff.width() - 1, diff.height() - 1)), kLabelBackground);
}

TEST(DifferenceImage, ColourBarMakesRoomOnShortImages) {
  const Image tiny(4, 3, vec4(0.2f));
  const Image diff = make_delta_e_image(tiny, tiny);
  EXPECT_GT(diff.height(), 3);
  EXPECT_GT(diff.width(), 4);
}

TEST(DifferenceImage, SignedLuminanceIsBlueWhereDarkerAndRedWhereBrighter) {
  const Image reference(3, 1, vec4(0.5f, 0.5f, 0.5f, 1.0f));
  Image test = reference;
  test.at(0, 0) = vec4(0.3f, 0.3f, 0.3f, 1.0f);
  test.at(2, 0) = vec4(0.7f, 0.7f, 0.7f, 1.0f);
  const Image diff = make_signed_luminance_image(test, reference, 0.1f);
  expect_rgb_near(diff.at(0, 0), map_color(ColorMap::cool_warm, 0.0f), 0.0f);
  expect_rgb_near(diff.at(1, 0), map_color(ColorMap::cool_warm, 0.5f), 0.0f);
  expect_rgb_near(diff.at(2, 0), map_color(ColorMap::cool_warm, 1.0f), 0.0f);
}

TEST(DifferenceImage, RejectsBadScalesAndSizes) {
  const Image a(4, 4);
  EXPECT_THROW(make_delta_e_image(a, a, 0.0f), InvalidArgument);
  EXPECT_THROW(make_signed_luminance_image(a, a, -1.0f), InvalidArgument);
  EXPECT_THROW(make_delta_e_image(a, Image(4, 5)), InvalidArgument);
}

}  // namespace
}  // namespace penumbra

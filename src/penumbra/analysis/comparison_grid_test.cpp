#include "penumbra/analysis/comparison_grid.h"

#include "penumbra/analysis/label_style.h"
#include "penumbra/analysis/text.h"
#include "penumbra/base/error.h"

#include <gtest/gtest.h>

namespace penumbra {
namespace {

int count_color(const Image& image, int x0, int y0, int x1, int y1, vec3 color) {
  int count = 0;
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) count += vec3(image.at(x, y)) == color ? 1 : 0;
  }
  return count;
}

TEST(ComparisonGrid, SizesCellsToTheLargestImageAndLabelsThem) {
  const vec3 red(1.0f, 0.0f, 0.0f), green(0.0f, 1.0f, 0.0f), blue(0.0f, 0.0f, 1.0f);
  const std::vector<LabeledImage> images = {
      {Image(20, 10, vec4(red, 0.0f)), "reference"},
      {Image(30, 16, vec4(green, 1.0f)), "shadow-rays\ndE 1.23"},
      {Image(12, 12, vec4(blue, 1.0f)), ""},
  };
  const Image grid = make_comparison_grid(images, 2);
  const ComparisonGridLayout layout = comparison_grid_layout(images, 2);

  // Two columns, two rows of 30 x 16 cells; the strip holds two lines of text.
  constexpr int gap = ComparisonGridLayout::kGap;
  const int label_height = kGlyphHeight + kLineAdvance + 2 * ComparisonGridLayout::kLabelPadding;
  EXPECT_EQ(layout.label_height, label_height);
  EXPECT_EQ(grid.width(), gap + 2 * (30 + gap));
  EXPECT_EQ(grid.height(), gap + 2 * (label_height + 16 + gap));
  EXPECT_EQ(grid.width(), layout.width);
  EXPECT_EQ(grid.height(), layout.height);

  // Images land whole in the image area of their cell, centred, and opaque.
  const ivec2 first = layout.cell_origin(0);
  EXPECT_EQ(count_color(grid, first.x, first.y + label_height, first.x + 30, first.y + label_height + 16, red),
            20 * 10);
  EXPECT_EQ(grid.at(first.x + 5, first.y + label_height + 3), vec4(red, 1.0f));
  const ivec2 second = layout.cell_origin(1);
  EXPECT_EQ(second, ivec2(gap + 30 + gap, gap));
  EXPECT_EQ(count_color(grid, 0, 0, grid.width(), grid.height(), green), 30 * 16);
  const ivec2 third = layout.cell_origin(2);
  EXPECT_EQ(third, ivec2(gap, gap + label_height + 16 + gap));
  EXPECT_EQ(count_color(grid, third.x, third.y + label_height, third.x + 30, third.y + label_height + 16, blue),
            12 * 12);

  // Label text sits in the strip above the image, and only there.
  const auto text_in = [&](ivec2 origin, int y0, int y1) {
    return count_color(grid, origin.x, origin.y + y0, origin.x + 30, origin.y + y1, kLabelText);
  };
  EXPECT_GT(text_in(first, 0, label_height), 20);
  EXPECT_GT(text_in(second, kLineAdvance + 2, label_height), 10);  // the second line "dE 1.23"
  EXPECT_EQ(text_in(third, 0, label_height), 0);
  EXPECT_EQ(vec3(grid.at(0, 0)), kLabelBackground);
  EXPECT_EQ(vec3(grid.at(grid.width() - 1, grid.height() - 1)), kLabelBackground);
}

TEST(ComparisonGrid, UsesNoMoreColumnsThanImages) {
  const std::vector<LabeledImage> images = {{Image(8, 8), "a"}, {Image(8, 8), "b"}};
  const Image grid = make_comparison_grid(images, 5);
  EXPECT_EQ(grid.width(), 4 + 2 * (8 + 4));
}

TEST(ComparisonGrid, CutsLabelsToTheCellWidth) {
  const std::vector<LabeledImage> images = {{Image(12, 12), "a very long technique name"}, {Image(12, 12), "b"}};
  const ComparisonGridLayout layout = comparison_grid_layout(images, 2);
  const Image grid = make_comparison_grid(images, 2);
  const ivec2 second = layout.cell_origin(1);
  // Nothing of the first label spills into the gap or the second cell's strip beyond its own 'b'.
  EXPECT_EQ(count_color(grid, second.x - ComparisonGridLayout::kGap, 0, second.x, layout.label_height, kLabelText), 0);
}

TEST(ComparisonGrid, EmptyListGivesAnEmptyImageAndBadColumnsThrow) {
  EXPECT_TRUE(make_comparison_grid({}, 3).empty());
  EXPECT_THROW(make_comparison_grid({{Image(2, 2), "x"}}, 0), InvalidArgument);
}

}  // namespace
}  // namespace penumbra

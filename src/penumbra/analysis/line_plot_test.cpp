// Line plots: tick selection, where series land, and bad input.
#include "penumbra/analysis/line_plot.h"

#include "penumbra/base/error.h"

#include <gtest/gtest.h>

#include <cmath>

namespace penumbra {
namespace {

TEST(LinePlot, TicksAreWholeMultiplesOfOneTwoOrFive) {
  EXPECT_EQ(plot_ticks(0.0, 8.0), (std::vector<double>{0, 2, 4, 6, 8}));
  const std::vector<double> unit = plot_ticks(0.0, 1.0);
  ASSERT_EQ(unit.size(), 6u);
  for (std::size_t i = 0; i < unit.size(); ++i) EXPECT_NEAR(unit[i], 0.2 * double(i), 1e-12);
  const std::vector<double> t = plot_ticks(0.13, 9.7);
  EXPECT_LE(t.front(), 0.13);
  EXPECT_GE(t.back(), 9.7);
  EXPECT_LE(t.size(), 6u);
  EXPECT_DOUBLE_EQ(t[1] - t[0], 2.0);
  const std::vector<double> single = plot_ticks(3.0, 3.0);  // widened about a single value
  EXPECT_LT(single.front(), 3.0);
  EXPECT_GT(single.back(), 3.0);
  EXPECT_THROW(plot_ticks(1.0, 0.0), InvalidArgument);
  EXPECT_THROW(plot_ticks(0.0, NAN), InvalidArgument);
}

// Count pixels of a series' colour inside a small window.
int plot_pixels_near(const Image& image, int cx, int cy, vec3 color) {
  int n = 0;
  for (int y = cy - 4; y <= cy + 4; ++y) {
    for (int x = cx - 4; x <= cx + 4; ++x) {
      if (x >= 0 && y >= 0 && x < image.width() && y < image.height() &&
          glm::length(vec3(image.at(x, y)) - color) < 1e-4f) {
        ++n;
      }
    }
  }
  return n;
}

TEST(LinePlot, SeriesAreDrawnWhereTheirValuesLie) {
  LinePlot plot;
  plot.series = {{"rising", {{0.0f, 0.0f}, {8.0f, 4.0f}}}, {"flat", {{0.0f, 4.0f}, {8.0f, 4.0f}}}};
  plot.title = "t";
  plot.x_label = "x";
  plot.y_label = "y";
  const Image image = draw_line_plot(plot);
  ASSERT_EQ(image.width(), plot.width);
  // Find the plot frame from the axes: the first column and the last row of
  // dark ink left/below the area, by locating the rising series' ends.
  int hits_low_left = 0, hits_top_right = 0, flat_at_top_left = 0;
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width() / 2; ++x) {
      if (plot_pixels_near(image, x, y, plot_color(0)) > 20 && y > image.height() / 2) ++hits_low_left;
      if (plot_pixels_near(image, x, y, plot_color(1)) > 20 && y < image.height() / 3) ++flat_at_top_left;
    }
    for (int x = image.width() / 2; x < image.width(); ++x) {
      if (plot_pixels_near(image, x, y, plot_color(0)) > 20 && y < image.height() / 3) ++hits_top_right;
    }
  }
  EXPECT_GT(hits_low_left, 0) << "the rising series starts low on the left";
  EXPECT_GT(hits_top_right, 0) << "and ends high on the right";
  EXPECT_GT(flat_at_top_left, 0) << "the flat series lies at the top (its value is the maximum)";
}

TEST(LinePlot, BadInputNamesTheSeries) {
  LinePlot plot;
  EXPECT_THROW(draw_line_plot(plot), InvalidArgument);
  plot.series = {{"empty", {}}};
  try {
    draw_line_plot(plot);
    ADD_FAILURE() << "no throw";
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.name(), "empty");
  }
  plot.series = {{"nan", {{0.0f, NAN}}}};
  EXPECT_THROW(draw_line_plot(plot), InvalidArgument);
  plot.series = {{"ok", {{0.0f, 1.0f}}}};
  plot.width = 10;
  EXPECT_THROW(draw_line_plot(plot), InvalidArgument);
}

}  // namespace
}  // namespace penumbra

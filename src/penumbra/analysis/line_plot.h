#pragma once
// Line plots drawn straight into an Image with the built-in bitmap font, for
// the figures docs/ shows (error against light size per technique, issue 18):
// linear axes with labelled ticks at 1, 2 or 5 times a power of ten, one
// polyline with a marker per point for each series, and a legend on the
// right. Colours cycle through ten categorical ones (kPlotColors); series 10
// and beyond repeat them with a hollow marker instead of a filled one.
#include "penumbra/base/math.h"
#include "penumbra/render/image.h"

#include <string>
#include <vector>

namespace penumbra {

struct PlotSeries {
  std::string name;
  std::vector<vec2> points;  // (x, y), drawn in this order
};

struct LinePlot {
  std::string title, x_label, y_label;
  std::vector<PlotSeries> series;
  int width = 720;
  int height = 420;
};

// Tick positions covering [lo, hi]: multiples of a step of 1, 2 or 5 times a
// power of ten giving at most `max_ticks` of them, extended outward to whole
// steps (the axis range is the first to the last). lo == hi widens to a
// unit range about it. Throws InvalidArgument for non-finite bounds, lo > hi
// or max_ticks < 2.
std::vector<double> plot_ticks(double lo, double hi, int max_ticks = 6);

// The plot on a white background. The y axis starts at 0 when no value is
// negative. Throws InvalidArgument (naming the series) for a series without
// points or with a non-finite coordinate, for no series at all, and for a
// size below 240 x 160 or above 8192 x 8192.
Image draw_line_plot(const LinePlot& plot);

// The colour of series i (linear RGB).
vec3 plot_color(std::size_t i);

}  // namespace penumbra

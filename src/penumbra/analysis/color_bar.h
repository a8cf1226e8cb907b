#pragma once
// A colour bar strip appended to the right of a false-colour image: the map
// from min_value (bottom) to max_value (top), tick marks and numeric labels.
#include "penumbra/analysis/color_map.h"
#include "penumbra/render/image.h"

#include <string>

namespace penumbra {

struct ColorBar {
  ColorMap map = ColorMap::viridis;
  float min_value = 0.0f;
  float max_value = 1.0f;
  std::string title;  // drawn above the bar, e.g. "dE2000"
};

// Where the strip and the bar land for an image of the given size (pixel
// rectangles are half-open: [bar_x0, bar_x1) x [bar_top, bar_bottom)).
struct ColorBarLayout {
  int width = 0;   // of the whole annotated image
  int height = 0;  // max(image height, the least height the bar needs)
  int bar_x0 = 0, bar_x1 = 0;
  int bar_top = 0, bar_bottom = 0;
  int tick_count = 0;
};

ColorBarLayout color_bar_layout(int image_width, int image_height, const ColorBar& bar);

// The image (copied at the top left, alpha set to 1) with the strip on its
// right on the label background. Throws InvalidArgument unless
// min_value < max_value, both finite.
Image append_color_bar(const Image& image, const ColorBar& bar);

}  // namespace penumbra

#include "penumbra/analysis/color_bar.h"

#include "penumbra/analysis/label_style.h"
#include "penumbra/analysis/text.h"
#include "penumbra/base/error.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace penumbra {
namespace {

constexpr int kMargin = 6;
constexpr int kBarWidth = 12;
constexpr int kTickLength = 3;
constexpr int kLabelGap = 3;
constexpr int kMinBarHeight = 40;
// Labels are centred on their tick; the glyph body (rows 0..6) has its middle
// at row 3, and half a glyph must fit above the top and below the bottom.
constexpr int kLabelCentre = 3;

std::vector<float> tick_values(const ColorBar& bar, int tick_count) {
  std::vector<float> values;
  for (int i = 0; i < tick_count; ++i) {
    const float f = float(i) / float(tick_count - 1);
    values.push_back(bar.min_value + f * (bar.max_value - bar.min_value));
  }
  return values;
}

std::string tick_label(float value) {
  // "{:.3g}" keeps labels short; -0 would read as a sign error.
  return fmt::format("{:.3g}", value == 0.0f ? 0.0f : value);
}

int tick_y(const ColorBarLayout& layout, int tick) {
  const float f = float(tick) / float(layout.tick_count - 1);
  return layout.bar_bottom - 1 - int(std::lround(f * float(layout.bar_bottom - layout.bar_top - 1)));
}

}  // namespace

ColorBarLayout color_bar_layout(int image_width, int image_height, const ColorBar& bar) {
  ColorBarLayout layout;
  const int title_height = bar.title.empty() ? 0 : text_height(bar.title) + kMargin;
  layout.bar_x0 = image_width + kMargin;
  layout.bar_x1 = layout.bar_x0 + kBarWidth;
  layout.bar_top = kMargin + title_height;
  layout.height = std::max(image_height, layout.bar_top + kMinBarHeight + kMargin);
  layout.bar_bottom = layout.height - kMargin;
  // Five ticks when there is room for a label every two line heights.
  layout.tick_count = layout.bar_bottom - layout.bar_top >= 5 * 2 * kLineAdvance ? 5 : 3;

  int label_width = 0;
  for (float v : tick_values(bar, layout.tick_count)) label_width = std::max(label_width, text_width(tick_label(v)));
  const int labels_right = layout.bar_x1 + kLabelGap + label_width;
  const int title_right = layout.bar_x0 + text_width(bar.title);
  layout.width = std::max(labels_right, title_right) + kMargin;
  return layout;
}

Image append_color_bar(const Image& image, const ColorBar& bar) {
  if (!std::isfinite(bar.min_value) || !std::isfinite(bar.max_value) || !(bar.min_value < bar.max_value)) {
    throw InvalidArgument("color_bar", fmt::format("needs finite min_value < max_value, got {} and {}",
                                                   bar.min_value, bar.max_value));
  }
  const ColorBarLayout layout = color_bar_layout(image.width(), image.height(), bar);
  Image out(layout.width, layout.height, vec4(kLabelBackground, 1.0f));
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) out.at(x, y) = vec4(vec3(image.at(x, y)), 1.0f);
  }

  const int bar_rows = layout.bar_bottom - layout.bar_top;
  for (int y = layout.bar_top; y < layout.bar_bottom; ++y) {
    const float t = float(layout.bar_bottom - 1 - y) / float(bar_rows - 1);
    const vec4 color(map_color(bar.map, t), 1.0f);
    for (int x = layout.bar_x0; x < layout.bar_x1; ++x) out.at(x, y) = color;
  }

  if (!bar.title.empty()) draw_text(out, layout.bar_x0, kMargin, bar.title, kLabelText);
  const std::vector<float> values = tick_values(bar, layout.tick_count);
  for (int i = 0; i < layout.tick_count; ++i) {
    const int y = tick_y(layout, i);
    // Ticks go on the left of the bar: beside a label they read as a minus sign.
    for (int x = layout.bar_x0 - kTickLength; x < layout.bar_x0; ++x) out.at(x, y) = vec4(kLabelText, 1.0f);
    draw_text(out, layout.bar_x1 + kLabelGap, y - kLabelCentre, tick_label(values[std::size_t(i)]), kLabelText);
  }
  return out;
}

}  // namespace penumbra

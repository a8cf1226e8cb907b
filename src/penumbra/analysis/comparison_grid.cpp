#include "penumbra/analysis/comparison_grid.h"

#include "penumbra/analysis/label_style.h"
#include "penumbra/analysis/text.h"
#include "penumbra/base/error.h"

#include <fmt/format.h>

#include <algorithm>
#include <string_view>

namespace penumbra {
namespace {

constexpr int kLargeTextCellWidth = 384;

// Cuts every line of `label` to at most `max_chars` characters.
std::string fit_lines(std::string_view label, int max_chars) {
  std::string fitted;
  int line_length = 0;
  for (char c : label) {
    if (c == '\n') {
      line_length = 0;
      fitted.push_back(c);
    } else if (line_length++ < max_chars) {
      fitted.push_back(c);
    }
  }
  return fitted;
}

}  // namespace

ivec2 ComparisonGridLayout::cell_origin(int index) const {
  const int column = index % columns;
  const int row = index / columns;
  return {kGap + column * (cell_width + kGap), kGap + row * (label_height + cell_height + kGap)};
}

ComparisonGridLayout comparison_grid_layout(const std::vector<LabeledImage>& images, int columns) {
  if (columns < 1) throw InvalidArgument("columns", fmt::format("must be >= 1, got {}", columns));
  ComparisonGridLayout layout;
  if (images.empty()) return layout;
  const int count = int(images.size());
  layout.columns = std::min(columns, count);
  layout.rows = (count + layout.columns - 1) / layout.columns;
  for (const LabeledImage& item : images) {
    layout.cell_width = std::max(layout.cell_width, item.image.width());
    layout.cell_height = std::max(layout.cell_height, item.image.height());
  }
  layout.text_scale = layout.cell_width >= kLargeTextCellWidth ? 2 : 1;
  int text_rows = text_height("X", layout.text_scale);
  for (const LabeledImage& item : images) text_rows = std::max(text_rows, text_height(item.label, layout.text_scale));
  layout.label_height = text_rows + 2 * ComparisonGridLayout::kLabelPadding;
  layout.width = ComparisonGridLayout::kGap + layout.columns * (layout.cell_width + ComparisonGridLayout::kGap);
  layout.height = ComparisonGridLayout::kGap +
                  layout.rows * (layout.label_height + layout.cell_height + ComparisonGridLayout::kGap);
  return layout;
}

Image make_comparison_grid(const std::vector<LabeledImage>& images, int columns) {
  const ComparisonGridLayout layout = comparison_grid_layout(images, columns);
  Image grid(layout.width, layout.height, vec4(kLabelBackground, 1.0f));
  const int usable_width = layout.cell_width - 2 * ComparisonGridLayout::kLabelPadding;
  const int max_chars = std::max(0, (usable_width / layout.text_scale + 1) / kCharAdvance);

  for (int i = 0; i < int(images.size()); ++i) {
    const Image& image = images[std::size_t(i)].image;
    const ivec2 origin = layout.cell_origin(i);
    draw_text(grid, origin.x + ComparisonGridLayout::kLabelPadding, origin.y + ComparisonGridLayout::kLabelPadding,
              fit_lines(images[std::size_t(i)].label, max_chars), kLabelText, layout.text_scale);
    const int x0 = origin.x + (layout.cell_width - image.width()) / 2;
    const int y0 = origin.y + layout.label_height + (layout.cell_height - image.height()) / 2;
    for (int y = 0; y < image.height(); ++y) {
      for (int x = 0; x < image.width(); ++x) grid.at(x0 + x, y0 + y) = vec4(vec3(image.at(x, y)), 1.0f);
    }
  }
  return grid;
}

}  // namespace penumbra

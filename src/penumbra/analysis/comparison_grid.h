#pragma once
// Side-by-side comparison sheet: images in a grid of cells, each with a label
// strip above it (technique name, its error), on the dark label background.
#include "penumbra/base/math.h"
#include "penumbra/render/image.h"

#include <string>
#include <vector>

namespace penumbra {

struct LabeledImage {
  Image image;
  std::string label;  // '\n' separates lines, e.g. "filtered-sat\ndE 1.23"
};

// Every cell is as large as the largest image (widest x highest) and images of
// any size are centred in theirs. Lines too long for a cell are cut.
struct ComparisonGridLayout {
  static constexpr int kGap = 4;           // around and between cells
  static constexpr int kLabelPadding = 3;  // around the text in a label strip
  int columns = 0;                         // min(requested columns, image count)
  int rows = 0;
  int cell_width = 0;
  int cell_height = 0;
  int text_scale = 1;    // 2 once cells are at least 384 pixels wide
  int label_height = 0;  // strip above each image: the tallest label (at least one line) plus padding
  int width = 0;
  int height = 0;

  // Top-left corner of cell `index`'s label strip; its image area starts
  // label_height pixels lower.
  ivec2 cell_origin(int index) const;
};

ComparisonGridLayout comparison_grid_layout(const std::vector<LabeledImage>& images, int columns);

// Throws InvalidArgument for columns < 1. No images give a 0 x 0 image. The
// grid is opaque: images are copied with alpha 1.
Image make_comparison_grid(const std::vector<LabeledImage>& images, int columns);

}  // namespace penumbra

#include "penumbra/analysis/text.h"

#include "penumbra/base/error.h"

#include <fmt/format.h>

#include <algorithm>

namespace penumbra {
namespace {

void check_scale(int scale) {
  if (scale < 1) throw InvalidArgument("scale", fmt::format("text scale must be >= 1, got {}", scale));
}

void fill_block(Image& image, int x0, int y0, int size, vec4 color) {
  const int x1 = std::min(x0 + size, image.width());
  const int y1 = std::min(y0 + size, image.height());
  for (int y = std::max(y0, 0); y < y1; ++y) {
    for (int x = std::max(x0, 0); x < x1; ++x) image.at(x, y) = color;
  }
}

}  // namespace

int text_width(std::string_view text, int scale) {
  check_scale(scale);
  std::size_t widest = 0;
  std::size_t line = 0;
  for (char c : text) {
    line = c == '\n' ? 0 : line + 1;
    widest = std::max(widest, line);
  }
  return widest == 0 ? 0 : (kCharAdvance * int(widest) - 1) * scale;
}

int text_height(std::string_view text, int scale) {
  check_scale(scale);
  if (text.empty()) return 0;
  const int extra_lines = int(std::count(text.begin(), text.end(), '\n'));
  return (kGlyphHeight + kLineAdvance * extra_lines) * scale;
}

void draw_text(Image& image, int x, int y, std::string_view text, vec3 color, int scale) {
  check_scale(scale);
  const vec4 ink(color, 1.0f);
  int pen_x = x;
  int pen_y = y;
  for (char c : text) {
    if (c == '\n') {
      pen_x = x;
      pen_y += kLineAdvance * scale;
      continue;
    }
    for (int row = 0; row < kGlyphHeight; ++row) {
      const std::uint8_t bits = glyph_row(c, row);
      for (int column = 0; column < kGlyphWidth; ++column) {
        if (bits & (1u << (kGlyphWidth - 1 - column))) {
          fill_block(image, pen_x + column * scale, pen_y + row * scale, scale, ink);
        }
      }
    }
    pen_x += kCharAdvance * scale;
  }
}

}  // namespace penumbra

#include "penumbra/analysis/text.h"

#include "penumbra/base/error.h"

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <set>

namespace penumbra {
namespace {

bool inked(const Image& image, int x, int y) { return image.at(x, y) != vec4(0.0f); }

int inked_count(const Image& image) {
  int count = 0;
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) count += inked(image, x, y) ? 1 : 0;
  }
  return count;
}

TEST(DrawText, InksTheGlyphAtScaleAndNothingOutsideItsBox) {
  Image image(40, 40, vec4(0.0f));
  const vec3 color(1.0f, 0.5f, 0.25f);
  const int x0 = 10, y0 = 12, scale = 2;
  draw_text(image, x0, y0, "A", color, scale);

  // 'A': top row ".###.", second row "#...#".
  EXPECT_EQ(image.at(x0 + 1 * scale, y0), vec4(color, 1.0f));
  EXPECT_TRUE(inked(image, x0 + 1 * scale + 1, y0 + 1));
  EXPECT_TRUE(inked(image, x0 + 3 * scale + 1, y0 + 1));
  EXPECT_FALSE(inked(image, x0, y0));
  EXPECT_FALSE(inked(image, x0 + 4 * scale + 1, y0 + 1));
  EXPECT_TRUE(inked(image, x0, y0 + 1 * scale));
  EXPECT_TRUE(inked(image, x0 + 4 * scale + 1, y0 + 1 * scale + 1));

  const int box_width = text_width("A", scale);
  const int box_height = text_height("A", scale);
  EXPECT_EQ(box_width, 5 * scale);
  EXPECT_EQ(box_height, 8 * scale);
  int bits = 0;
  for (int row = 0; row < kGlyphHeight; ++row) bits += std::popcount(unsigned(glyph_row('A', row)));
  EXPECT_EQ(inked_count(image), bits * scale * scale);
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      const bool inside = x >= x0 && x < x0 + box_width && y >= y0 && y < y0 + box_height;
      if (!inside) {
        EXPECT_FALSE(inked(image, x, y)) << x << "," << y;
      }
    }
  }
}

TEST(DrawText, AdvancesCharactersAndLines) {
  EXPECT_EQ(text_width("", 1), 0);
  EXPECT_EQ(text_height("", 1), 0);
  EXPECT_EQ(text_width("dE 1.23", 1), 7 * kCharAdvance - 1);
  EXPECT_EQ(text_width("abc\nd", 3), (3 * kCharAdvance - 1) * 3);
  EXPECT_EQ(text_height("abc\nd", 1), kGlyphHeight + kLineAdvance);

  Image image(30, 30, vec4(0.0f));
  draw_text(image, 0, 0, "II\nI", vec3(1.0f), 1);
  // 'I' has a full-width-3 top bar at columns 1..3 of its cell.
  EXPECT_TRUE(inked(image, 1, 0));
  EXPECT_TRUE(inked(image, kCharAdvance + 1, 0));
  EXPECT_TRUE(inked(image, 1, kLineAdvance));
  EXPECT_FALSE(inked(image, kCharAdvance + 1, kLineAdvance));
}

TEST(DrawText, ClipsAtTheImageBorder) {
  Image image(8, 8, vec4(0.0f));
  draw_text(image, -3, -4, "W#", vec3(1.0f), 2);
  draw_text(image, 6, 6, "M", vec3(1.0f), 3);
  EXPECT_GT(inked_count(image), 0);
  EXPECT_THROW(draw_text(image, 0, 0, "x", vec3(1.0f), 0), InvalidArgument);
}

TEST(BitmapFont, EveryPrintableCharacterHasItsOwnGlyph) {
  std::set<std::uint64_t> seen;  // a glyph's eight rows packed into one word
  for (int c = 32; c <= 126; ++c) {
    std::uint64_t packed = 0;
    int bits = 0;
    for (int row = 0; row < kGlyphHeight; ++row) {
      const std::uint8_t mask = glyph_row(char(c), row);
      EXPECT_LT(mask, 1u << kGlyphWidth);
      bits += std::popcount(unsigned(mask));
      packed = (packed << 8) | mask;
    }
    EXPECT_EQ(bits == 0, c == ' ') << char(c);
    EXPECT_TRUE(seen.insert(packed).second) << "glyph of '" << char(c) << "' repeats another";
  }
  for (int row = 0; row < kGlyphHeight; ++row) EXPECT_EQ(glyph_row('\t', row), glyph_row('?', row));
}

}  // namespace
}  // namespace penumbra

#pragma once
// A built-in 5 x 8 bitmap font for ASCII 32..126, so that grids and colour
// bars can be labelled without a font dependency. Rows 0..6 lie above the
// baseline (capitals and digits fill them), row 7 holds descenders.
#include <cstdint>

namespace penumbra {

inline constexpr int kGlyphWidth = 5;
inline constexpr int kGlyphHeight = 8;

// Bit (kGlyphWidth - 1 - column) of the result is set where the glyph is
// inked, i.e. the most significant of the five bits is the leftmost column.
// Characters outside 32..126 are drawn as '?'.
std::uint8_t glyph_row(char c, int row);

}  // namespace penumbra

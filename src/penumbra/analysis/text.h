#pragma once
// Labels drawn straight into an Image with the built-in bitmap font. A
// character advances kCharAdvance x scale pixels, a line kLineAdvance x scale;
// '\n' starts a new line.
#include "penumbra/analysis/bitmap_font.h"
#include "penumbra/base/math.h"
#include "penumbra/render/image.h"

#include <string_view>

namespace penumbra {

inline constexpr int kCharAdvance = kGlyphWidth + 1;
inline constexpr int kLineAdvance = kGlyphHeight + 1;

// Size of the box that draw_text can ink: the widest line is
// (kCharAdvance n - 1) x scale wide, the box is kGlyphHeight x scale high for
// one line plus kLineAdvance x scale per further line. Empty text is 0 x 0.
int text_width(std::string_view text, int scale = 1);
int text_height(std::string_view text, int scale = 1);

// Sets the inked pixels (scale x scale blocks per font pixel) of the box whose
// top-left corner is (x, y) to `color` with alpha 1; other pixels are left as
// they are, and anything outside the image is clipped. Throws
// InvalidArgument for scale < 1.
void draw_text(Image& image, int x, int y, std::string_view text, vec3 color, int scale = 1);

}  // namespace penumbra

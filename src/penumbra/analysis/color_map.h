#pragma once
// Colour maps for false-colour images. Both are interpolated between published
// anchor colours in sRGB-encoded space and returned as linear rgb (Image is
// linear), so a PNG shows the anchors exactly.
#include "penumbra/base/math.h"

namespace penumbra {

enum class ColorMap {
  // Sequential, lightness increasing monotonically, readable by colour-blind
  // viewers: viridis (S. van der Walt and N. Smith, matplotlib 2.0, 2015).
  viridis,
  // Diverging, blue - light grey - red with the neutral middle at t = 0.5:
  // K. Moreland, "Diverging Color Maps for Scientific Visualization", 2009.
  cool_warm,
};

// t is clamped to [0, 1]; NaN maps to magenta, which neither map contains.
vec3 map_color(ColorMap map, float t);

}  // namespace penumbra

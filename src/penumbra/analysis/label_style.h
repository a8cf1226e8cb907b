#pragma once
// Colours shared by the annotated images (grids, colour bars), so that they
// look alike side by side. Linear values: 0.02 and 0.8 encode to about sRGB
// 39 and 231 of 255.
#include "penumbra/base/math.h"

namespace penumbra {

inline constexpr vec3 kLabelBackground{0.02f, 0.02f, 0.02f};
inline constexpr vec3 kLabelText{0.8f, 0.8f, 0.8f};

}  // namespace penumbra

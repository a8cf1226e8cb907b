#pragma once
// False-colour difference images for looking at where a technique departs
// from the reference, each with a labelled colour bar on the right (see
// color_bar.h for the layout). Pixel (x, y) of the inputs is pixel (x, y) of
// the result; alpha is 1 everywhere. Both throw InvalidArgument for images of
// different sizes, empty images, or a scale that is not positive and finite.
#include "penumbra/analysis/color_bar.h"
#include "penumbra/render/image.h"

namespace penumbra {

// Per-pixel CIEDE2000 (as in delta_e_2000_per_pixel) through viridis, from 0
// (the map's first colour) to max_delta_e; larger differences saturate.
Image make_delta_e_image(const Image& test, const Image& reference, float max_delta_e = 10.0f);

// Linear luminance test - reference through the cool-warm map: blue where the
// test is darker (e.g. too much shadow), red where it is brighter, neutral
// grey where they agree; +-max_difference saturate. Linear rather than encoded
// luminance, because shadow errors are errors in transported energy.
Image make_signed_luminance_image(const Image& test, const Image& reference, float max_difference = 0.1f);

}  // namespace penumbra

#pragma once
// One-dimensional views of an image for frequency tests: the luminance along
// a row (e.g. across a shadow cast by the chirp occluder) and its spectrum.
#include "penumbra/render/image.h"

#include <vector>

namespace penumbra {

// Linear Rec. 709 luminance of every pixel of `row` (0 = top), left to right.
// Throws InvalidArgument for a row outside the image.
std::vector<float> row_luminance(const Image& image, int row);

// Amplitudes of the real discrete Fourier transform of `signal` (n samples),
// bins k = 0 .. n/2, bin k meaning k cycles over the whole signal. Scaled so
// that A cos(2 pi k i / n + phase) gives A in bin k: |X_k| 2 / n, except
// |X_0| / n (the mean) and, for even n, |X_{n/2}| / n. Plain O(n^2) DFT in
// double with exact twiddle factors (index j k mod n): profiles are a few
// thousand samples and this needs no power-of-two length. Empty in, empty out.
std::vector<float> amplitude_spectrum(const std::vector<float>& signal);

}  // namespace penumbra

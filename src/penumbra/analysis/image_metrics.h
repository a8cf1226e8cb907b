#pragma once
// Full-reference image metrics: how far a technique's image is from the
// reference image. All of them take two linear images of the same size (they
// throw InvalidArgument naming both sizes otherwise, and for empty images) and
// ignore alpha.
#include "penumbra/analysis/color_difference.h"
#include "penumbra/analysis/color_space.h"
#include "penumbra/render/image.h"

#include <vector>

namespace penumbra {

// Pixel errors over the linear R, G and B values (3 samples per pixel).
double rmse(const Image& test, const Image& reference);
// 10 log10(peak^2 / MSE) with peak 1.0 (linear radiance 1 = display white);
// +infinity for identical images.
double psnr(const Image& test, const Image& reference);
double mean_absolute_error(const Image& test, const Image& reference);
double max_abs_error(const Image& test, const Image& reference);

// Mean SSIM (Z. Wang, A. C. Bovik, H. R. Sheikh, E. P. Simoncelli, "Image
// quality assessment: from error visibility to structural similarity", IEEE
// TIP 13(4), 2004) on the luma Y' = 0.2126 R' + 0.7152 G' + 0.0722 B' of the
// sRGB-encoded image (linear values clamped to [0, 1], then encoded), which is
// what a viewer of the PNG sees. Standard parameters: 11 x 11 Gaussian window
// with sigma 1.5, K1 = 0.01, K2 = 0.03, L = 1, averaged over every window
// position that lies inside the image (as in the authors' ssim_index.m; no
// down-sampling). An image narrower or lower than 11 pixels uses the Gaussian
// truncated to the image in that direction. Identical images give exactly 1.
double ssim(const Image& test, const Image& reference);

// Per-pixel CIEDE2000 between the two images, row-major. Linear colours are
// clamped to [0, 1] before conversion to L*a*b*: sRGB L*a*b* is only defined
// for the gamut, and a display clips the same way. NaN channels stay NaN.
std::vector<float> delta_e_2000_per_pixel(const Image& test, const Image& reference);

struct DeltaEStats {
  double mean = 0.0;
  double median = 0.0;
  double p99 = 0.0;  // 99th percentile
  double max = 0.0;
};

// Statistics of delta_e_2000_per_pixel. Percentiles interpolate linearly
// between order statistics (position p (n - 1), numpy's default). A NaN pixel
// makes every statistic NaN, so a broken render is never averaged away.
DeltaEStats delta_e_stats(const Image& test, const Image& reference);
DeltaEStats delta_e_stats(std::vector<float> per_pixel_delta_e);

struct ImageComparison {
  double rmse = 0.0;
  double psnr = 0.0;
  double ssim = 0.0;
  double mean_de = 0.0;    // CIEDE2000
  double median_de = 0.0;
  double p99_de = 0.0;
  double max_de = 0.0;
  double mae = 0.0;
};

// All of the metrics above for one pair of images.
ImageComparison compare_images(const Image& test, const Image& reference);

// Throws InvalidArgument unless both images are non-empty and of one size.
void check_same_size(const Image& test, const Image& reference);

}  // namespace penumbra

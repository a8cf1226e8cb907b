// Mean SSIM; the definition and parameters are documented in image_metrics.h.
#include "penumbra/analysis/image_metrics.h"

#include "penumbra/base/parallel.h"

#include <algorithm>
#include <cmath>

namespace penumbra {
namespace {

constexpr int kWindow = 11;
constexpr double kSigma = 1.5;
constexpr double kC1 = (0.01 * 1.0) * (0.01 * 1.0);  // (K1 L)^2
constexpr double kC2 = (0.03 * 1.0) * (0.03 * 1.0);  // (K2 L)^2

std::vector<double> encoded_luma(const Image& image) {
  std::vector<double> luma(image.pixel_count());
  for (std::size_t i = 0; i < luma.size(); ++i) {
    luma[i] = luminance(srgb_encode(vec3(image.pixels()[i])));
  }
  return luma;
}

// Normalised 1D Gaussian of `size` taps centred on the window.
std::vector<double> gaussian_taps(int size) {
  std::vector<double> taps(std::size_t(size), 0.0);
  const double centre = 0.5 * double(size - 1);
  double sum = 0.0;
  for (int i = 0; i < size; ++i) {
    const double d = double(i) - centre;
    taps[std::size_t(i)] = std::exp(-d * d / (2.0 * kSigma * kSigma));
    sum += taps[std::size_t(i)];
  }
  for (double& t : taps) t /= sum;
  return taps;
}

// The five local moments SSIM needs, filtered along one row.
struct RowMoments {
  std::vector<double> x, y, xx, yy, xy;
  explicit RowMoments(std::size_t n) : x(n), y(n), xx(n), yy(n), xy(n) {}
};

struct SsimInput {
  const std::vector<double>& x;
  const std::vector<double>& y;
  int width;
  const std::vector<double>& taps_x;
  const std::vector<double>& taps_y;
};

void filter_row(const SsimInput& in, int row, RowMoments& out) {
  const std::size_t offset = std::size_t(row) * std::size_t(in.width);
  const std::size_t valid = out.x.size();
  for (std::size_t col = 0; col < valid; ++col) {
    double x = 0.0, y = 0.0, xx = 0.0, yy = 0.0, xy = 0.0;
    for (std::size_t k = 0; k < in.taps_x.size(); ++k) {
      const double w = in.taps_x[k];
      const double a = in.x[offset + col + k];
      const double b = in.y[offset + col + k];
      x += w * a;
      y += w * b;
      xx += w * a * a;
      yy += w * b * b;
      xy += w * a * b;
    }
    out.x[col] = x;
    out.y[col] = y;
    out.xx[col] = xx;
    out.yy[col] = yy;
    out.xy[col] = xy;
  }
}

// Sum of the SSIM map over output rows [first, last). Keeps only the window's
// rows of horizontally filtered moments, so memory stays O(window x width).
double ssim_rows(const SsimInput& in, int first, int last) {
  const int window_rows = int(in.taps_y.size());
  const std::size_t valid = std::size_t(in.width) - in.taps_x.size() + 1;
  const std::size_t ring_size = static_cast<std::size_t>(window_rows);
  std::vector<RowMoments> ring(ring_size, RowMoments(valid));
  for (int r = first; r < first + window_rows - 1; ++r) filter_row(in, r, ring[std::size_t(r % window_rows)]);

  double sum = 0.0;
  for (int out_row = first; out_row < last; ++out_row) {
    const int newest = out_row + window_rows - 1;
    filter_row(in, newest, ring[std::size_t(newest % window_rows)]);
    for (std::size_t col = 0; col < valid; ++col) {
      double mx = 0.0, my = 0.0, mxx = 0.0, myy = 0.0, mxy = 0.0;
      for (int k = 0; k < window_rows; ++k) {
        const RowMoments& m = ring[std::size_t((out_row + k) % window_rows)];
        const double w = in.taps_y[std::size_t(k)];
        mx += w * m.x[col];
        my += w * m.y[col];
        mxx += w * m.xx[col];
        myy += w * m.yy[col];
        mxy += w * m.xy[col];
      }
      const double var_x = mxx - mx * mx;
      const double var_y = myy - my * my;
      const double cov = mxy - mx * my;
      sum += ((2.0 * mx * my + kC1) * (2.0 * cov + kC2)) / ((mx * mx + my * my + kC1) * (var_x + var_y + kC2));
    }
  }
  return sum;
}

}  // namespace

double ssim(const Image& test, const Image& reference) {
  check_same_size(test, reference);
  const std::vector<double> x = encoded_luma(test);
  const std::vector<double> y = encoded_luma(reference);
  // Per window the ratio is 1 only up to rounding (and FMA contraction may
  // round numerator and denominator differently); identical inputs must
  // compare exactly equal, so they are answered directly.
  if (x == y) return 1.0;

  const std::vector<double> taps_x = gaussian_taps(std::min(kWindow, test.width()));
  const std::vector<double> taps_y = gaussian_taps(std::min(kWindow, test.height()));
  const SsimInput in{x, y, test.width(), taps_x, taps_y};
  const int out_width = test.width() - int(taps_x.size()) + 1;
  const int out_height = test.height() - int(taps_y.size()) + 1;

  // Fixed blocks summed in order, so the result does not depend on scheduling.
  constexpr int kBlockRows = 32;
  const int blocks = (out_height + kBlockRows - 1) / kBlockRows;
  std::vector<double> block_sums(std::size_t(blocks), 0.0);
  parallel_for(0, blocks, [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t b = first; b < last; ++b) {
      const int row0 = int(b) * kBlockRows;
      block_sums[std::size_t(b)] = ssim_rows(in, row0, std::min(row0 + kBlockRows, out_height));
    }
  });
  double sum = 0.0;
  for (double s : block_sums) sum += s;
  return sum / (double(out_width) * double(out_height));
}

}  // namespace penumbra

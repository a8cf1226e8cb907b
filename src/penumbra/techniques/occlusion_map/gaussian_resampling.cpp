#include "penumbra/techniques/occlusion_map/gaussian_resampling.h"

#include "penumbra/base/error.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace penumbra {

double ResamplingTaps::position(int j) const {
  if (n_out <= 1) return 0.5 * double(n_in - 1);
  return double(j) * double(n_in - 1) / double(n_out - 1);
}

ResamplingTaps gaussian_resampling_taps(int n_in, int n_out, double sigma_in) {
  if (n_in < 1 || n_out < 1) {
    throw InvalidArgument("resolution", fmt::format("resampling {} nodes to {}: both must be at least 1", n_in, n_out));
  }
  if (!(sigma_in > 0.0) || !std::isfinite(sigma_in)) {
    throw InvalidArgument("kernel_size", fmt::format("Gaussian sigma must be positive (got {})", sigma_in));
  }
  ResamplingTaps taps;
  taps.n_in = n_in;
  taps.n_out = n_out;
  taps.first.resize(std::size_t(n_out));
  taps.begin.resize(std::size_t(n_out) + 1);
  const double radius = kKernelRadiusSigmas * sigma_in;
  for (int j = 0; j < n_out; ++j) {
    const double x = taps.position(j);
    // A small tolerance keeps the taps at exactly 2 sigma (the 5-tap kernel's ends).
    int lo = std::max(0, int(std::ceil(x - radius - 1e-9)));
    int hi = std::min(n_in - 1, int(std::floor(x + radius + 1e-9)));
    if (lo > hi) lo = hi = std::clamp(int(std::lround(x)), 0, n_in - 1);  // narrower than the node spacing
    taps.first[std::size_t(j)] = lo;
    taps.begin[std::size_t(j)] = int(taps.weights.size());
    double sum = 0.0;
    for (int i = lo; i <= hi; ++i) sum += std::exp(-0.5 * (double(i) - x) * (double(i) - x) / (sigma_in * sigma_in));
    for (int i = lo; i <= hi; ++i) {
      taps.weights.push_back(float(std::exp(-0.5 * (double(i) - x) * (double(i) - x) / (sigma_in * sigma_in)) / sum));
    }
  }
  taps.begin[std::size_t(n_out)] = int(taps.weights.size());
  return taps;
}

std::vector<double> dense_weights(const ResamplingTaps& taps) {
  std::vector<double> m(std::size_t(taps.n_out) * std::size_t(taps.n_in), 0.0);
  for (int j = 0; j < taps.n_out; ++j) {
    for (int t = 0; t < taps.count(j); ++t) {
      m[std::size_t(j) * std::size_t(taps.n_in) + std::size_t(taps.first[std::size_t(j)] + t)] =
          taps.weights[std::size_t(taps.begin[std::size_t(j)] + t)];
    }
  }
  return m;
}

std::vector<double> compose_weights(const std::vector<double>& outer, int outer_rows, const std::vector<double>& inner,
                                    int inner_rows, int inner_cols) {
  std::vector<double> m(std::size_t(outer_rows) * std::size_t(inner_cols), 0.0);
  for (int r = 0; r < outer_rows; ++r) {
    for (int k = 0; k < inner_rows; ++k) {
      const double a = outer[std::size_t(r) * std::size_t(inner_rows) + std::size_t(k)];
      if (a == 0.0) continue;
      for (int c = 0; c < inner_cols; ++c) {
        m[std::size_t(r) * std::size_t(inner_cols) + std::size_t(c)] +=
            a * inner[std::size_t(k) * std::size_t(inner_cols) + std::size_t(c)];
      }
    }
  }
  return m;
}

}  // namespace penumbra

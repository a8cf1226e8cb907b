#include "penumbra/techniques/convolution/kernels_1d.h"

#include "penumbra/base/rng.h"

#include <algorithm>
#include <cmath>

namespace penumbra {

double Taps1D::mean() const {
  double m = 0.0;
  for (std::size_t i = 0; i < offsets.size(); ++i) m += weights[i] * offsets[i];
  return m;
}

double Taps1D::variance() const {
  const double m = mean();
  double v = 0.0;
  for (std::size_t i = 0; i < offsets.size(); ++i) v += weights[i] * (offsets[i] - m) * (offsets[i] - m);
  return v;
}

Taps1D kernel_1d_taps(Kernel1D kernel, int mu, double sigma, int iteration, std::uint64_t seed) {
  Taps1D taps;
  switch (kernel) {
    case Kernel1D::TopHat: {
      // An odd number m of unit cells has variance (m^2 - 1) / 12 = sigma^2.
      int half = int(std::lround(0.5 * (std::sqrt(12.0 * sigma * sigma + 1.0) - 1.0)));
      half = std::max(half, 0);
      for (int o = -half; o <= half; ++o) {
        taps.offsets.push_back(mu + o);
        taps.weights.push_back(1.0 / double(2 * half + 1));
      }
      break;
    }
    case Kernel1D::Dirac: {
      const int s = int(std::lround(sigma));
      taps.offsets = {mu - s, mu + s};
      taps.weights = {0.5, 0.5};
      break;
    }
    case Kernel1D::StochasticDirac: {
      const int s = int(std::lround(sigma));
      // P(s - 1) = 1/2 + 1/(4s), P(s + 1) = 1/2 - 1/(4s): E[r^2] = s^2.
      Pcg32 rng(mix_bits(seed * 0x9e3779b97f4a7c15ULL + std::uint64_t(iteration)));
      const double p_inner = s > 0 ? 0.5 + 0.25 / double(s) : 0.0;
      const int r = s <= 0 ? 0 : (double(rng.next_float()) < p_inner ? s - 1 : s + 1);
      taps.offsets = {mu - r, mu + r};
      taps.weights = {0.5, 0.5};
      break;
    }
  }
  return taps;
}

std::vector<double> convolve_1d(const std::vector<double>& signal, const Taps1D& taps) {
  const int n = int(signal.size());
  std::vector<double> out(signal.size(), 0.0);
  for (int x = 0; x < n; ++x) {
    double sum = 0.0;
    for (std::size_t j = 0; j < taps.offsets.size(); ++j) {
      sum += taps.weights[j] * signal[std::size_t(std::clamp(x - taps.offsets[j], 0, n - 1))];
    }
    out[std::size_t(x)] = sum;
  }
  return out;
}

std::vector<double> iterate_1d(std::vector<double> signal, Kernel1D kernel, int mu, double sigma, int n,
                               std::uint64_t seed) {
  for (int i = 0; i < n; ++i) signal = convolve_1d(signal, kernel_1d_taps(kernel, mu, sigma, i, seed));
  return signal;
}

}  // namespace penumbra

#pragma once
// The 1D kernels of Table I (Patel et al. 2013, section 3.3), all of mean mu
// and variance sigma^2, for the 1D analysis of iterated convolution (Fig. 3):
//   top-hat           box of width sqrt(12) sigma, one sample per cell;
//   Dirac             two samples at mu -+ sigma (width 2 sigma);
//   stochastic Dirac  two samples at mu -+ r with r drawn per iteration from
//                     {sigma - 1, sigma + 1} so that E[r^2] = sigma^2
//                     (width 2 sigma +- 2).
// Signals live on an integer grid (one sample per cell); offsets are integers
// (sigma and mu are rounded to cells for Dirac and the stochastic Dirac, and
// the top-hat has an odd integer width) so no interpolation adds variance.
// Outside the grid the signal is held at its edge values (a Heaviside stays one).
#include <cstdint>
#include <string>
#include <vector>

namespace penumbra {

enum class Kernel1D { TopHat, Dirac, StochasticDirac };

struct Taps1D {
  std::vector<int> offsets;
  std::vector<double> weights;  // sum to one

  double mean() const;
  double variance() const;
};

// The taps of one iteration; `iteration` and `seed` pick the stochastic radius.
Taps1D kernel_1d_taps(Kernel1D kernel, int mu, double sigma, int iteration, std::uint64_t seed);

// out[x] = sum_j w_j in[x - o_j] (the signal moves by +mean per iteration).
std::vector<double> convolve_1d(const std::vector<double>& signal, const Taps1D& taps);

// Iterates the kernel n times over the signal.
std::vector<double> iterate_1d(std::vector<double> signal, Kernel1D kernel, int mu, double sigma, int n,
                               std::uint64_t seed = 1);

}  // namespace penumbra

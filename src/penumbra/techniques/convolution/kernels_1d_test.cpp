#include "penumbra/techniques/convolution/kernels_1d.h"

#include <gtest/gtest.h>

#include <cmath>

namespace penumbra {
namespace {

// Mean and variance of the pdf behind an iterated Heaviside: its derivative.
void cdf_moments(const std::vector<double>& cdf, double& mean, double& variance) {
  double m0 = 0.0, m1 = 0.0, m2 = 0.0;
  for (std::size_t x = 1; x < cdf.size(); ++x) {
    const double p = cdf[x] - cdf[x - 1];  // mass between cells x-1 and x
    const double pos = double(x) - 0.5;
    m0 += p;
    m1 += p * pos;
    m2 += p * pos * pos;
  }
  mean = m1 / m0;
  variance = m2 / m0 - mean * mean;
}

std::vector<double> heaviside(int n, int at) {
  std::vector<double> s(std::size_t(n), 0.0);
  for (int x = at; x < n; ++x) s[std::size_t(x)] = 1.0;
  return s;
}

TEST(ConvolutionKernels1D, TableOneKernelsHaveTheRequestedMoments) {
  for (Kernel1D k : {Kernel1D::TopHat, Kernel1D::Dirac}) {
    const Taps1D t = kernel_1d_taps(k, 2, 5.0, 0, 1);
    EXPECT_DOUBLE_EQ(t.mean(), 2.0);
    // Top-hat: 17 cells have variance (17^2 - 1) / 12 = 24 (sigma^2 = 25);
    // Dirac: exactly sigma^2.
    EXPECT_NEAR(t.variance(), 25.0, k == Kernel1D::TopHat ? 1.01 : 1e-12);
  }
  // Stochastic Dirac: E[r^2] = sigma^2 over many draws; width 2 sigma +- 2.
  double sum = 0.0;
  const int draws = 20000;
  for (int i = 0; i < draws; ++i) {
    const Taps1D t = kernel_1d_taps(Kernel1D::StochasticDirac, 0, 5.0, i, 7);
    EXPECT_EQ(t.mean(), 0.0);
    const int width = t.offsets[1] - t.offsets[0];
    EXPECT_TRUE(width == 8 || width == 12);
    sum += t.variance();
  }
  EXPECT_NEAR(sum / draws, 25.0, 0.1);  // std error of the mean: 5 * 2 / sqrt(20000) = 0.07
}

// Iterating a kernel n times gives mean n mu and variance n sigma^2 (eq. 13).
TEST(ConvolutionKernels1D, IteratedMomentsAddUp) {
  const int n = 100, size = 1200, edge = 300;
  for (Kernel1D k : {Kernel1D::TopHat, Kernel1D::Dirac, Kernel1D::StochasticDirac}) {
    const Taps1D one = kernel_1d_taps(k, 3, 5.0, 0, 1);
    const std::vector<double> r = iterate_1d(heaviside(size, edge), k, 3, 5.0, n, 1);
    double mean = 0.0, var = 0.0;
    cdf_moments(r, mean, var);
    // The step of the Heaviside lies between cells edge - 1 and edge.
    EXPECT_NEAR(mean - (edge - 0.5), n * 3.0, 1e-6) << int(k);
    if (k == Kernel1D::StochasticDirac) {
      // Realised variances differ from 25 by +-(2 s +- 1) per draw: over 100
      // draws the sum's sd is about 10 * 10 = 100 (4% of 2500).
      EXPECT_NEAR(var, n * 25.0, 300.0);
    } else {
      EXPECT_NEAR(var, n * one.variance(), 1e-6 * n * one.variance()) << int(k);
    }
  }
}

// Fig. 3: all three converge to the same Gaussian cdf; the static Dirac
// kernel least well (its result lives on a lattice of spacing 2 sigma).
TEST(ConvolutionKernels1D, AllKernelsConvergeToTheSameGaussian) {
  const int n = 100, size = 1000, edge = 500;
  const double sigma = 5.0;
  double error[3];
  for (Kernel1D k : {Kernel1D::TopHat, Kernel1D::Dirac, Kernel1D::StochasticDirac}) {
    const std::vector<double> r = iterate_1d(heaviside(size, edge), k, 0, sigma, n, 3);
    // The stochastic Dirac's variance is sigma^2 in expectation only.
    const double var =
        k == Kernel1D::StochasticDirac ? n * sigma * sigma : n * kernel_1d_taps(k, 0, sigma, 0, 3).variance();
    double worst = 0.0;
    for (int x = 0; x < size; ++x) {
      const double g = 0.5 * std::erfc(-(double(x) - edge + 0.5) / std::sqrt(2.0 * var));
      worst = std::max(worst, std::abs(r[std::size_t(x)] - g));
    }
    error[int(k)] = worst;
  }
  EXPECT_LT(error[int(Kernel1D::TopHat)], 0.01);
  EXPECT_LT(error[int(Kernel1D::StochasticDirac)], 0.03);
  EXPECT_LT(error[int(Kernel1D::Dirac)], 0.08);
  EXPECT_LT(error[int(Kernel1D::StochasticDirac)], error[int(Kernel1D::Dirac)]);
  RecordProperty("max_cdf_error_tophat", std::to_string(error[0]));
  std::printf("max |cdf - Gaussian|: top-hat %.4f, Dirac %.4f, stochastic Dirac %.4f\n", error[0], error[1], error[2]);
}

}  // namespace
}  // namespace penumbra

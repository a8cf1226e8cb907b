#include "penumbra/techniques/convolution/slab_kernel.h"

#include "penumbra/techniques/convolution/gaussian_light.h"

#include <gtest/gtest.h>

namespace penumbra {
namespace {

struct Moments {
  glm::dvec2 mean{0.0};
  glm::dmat2 cov{0.0};
};

// Mean and covariance of the taps, averaged over slabs (ellipse offsets) and
// pixels (Poisson rotations).
Moments kernel_moments(SlabKernelType type, int samples, vec2 mean, const glm::mat2& cov) {
  SlabKernelBuilder b(type, samples, mean, cov, 11);
  Moments m;
  double total = 0.0;
  std::vector<std::pair<glm::dvec2, double>> taps;
  for (int slab = 0; slab < 400; ++slab) {
    const SlabKernel k = b.for_slab(slab);
    for (int px = 0; px < 8; ++px) {
      const float phi = k.pixel_angle(px, slab);
      for (int j = 0; j < k.count; ++j) {
        taps.push_back({glm::dvec2(k.offset(j, std::cos(phi), std::sin(phi))), double(k.weights[j])});
        total += k.weights[j];
      }
    }
  }
  for (auto& [p, w] : taps) m.mean += w * p / total;
  for (auto& [p, w] : taps) {
    const glm::dvec2 d = p - m.mean;
    m.cov += w * glm::outerProduct(d, d) / total;
  }
  return m;
}

// Every kernel has the mean and covariance of eq. 7/15 (e mu, d1 e Sigma):
// the Gaussian exactly, the ellipse over its random offsets, the Poisson disk
// over its random rotations (3200 draws: a few percent of sampling noise).
TEST(ConvolutionSlabKernel, KernelsHaveTheRequestedMeanAndCovariance) {
  const vec2 mean(0.7f, -0.3f);
  const glm::mat2 cov = rotated_covariance(4.0f, 1.0f, 30.0f);
  struct Case {
    SlabKernelType type;
    int samples;
    double tolerance;
  };
  for (const Case& c : {Case{SlabKernelType::Gaussian, 19, 1e-4}, Case{SlabKernelType::Ellipse, 2, 0.04},
                        Case{SlabKernelType::Ellipse, 3, 0.04}, Case{SlabKernelType::Poisson, 8, 0.06},
                        Case{SlabKernelType::Poisson, 16, 0.06}}) {
    const Moments m = kernel_moments(c.type, c.samples, mean, cov);
    EXPECT_NEAR(m.mean.x, mean.x, 0.05) << int(c.type) << " " << c.samples;
    EXPECT_NEAR(m.mean.y, mean.y, 0.05) << int(c.type) << " " << c.samples;
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) EXPECT_NEAR(m.cov[i][j], cov[i][j], c.tolerance * 4.0) << int(c.type) << " " << c.samples;
  }
}

TEST(ConvolutionSlabKernel, ZeroVarianceIsOneTapAtTheMean) {
  for (SlabKernelType t : {SlabKernelType::Gaussian, SlabKernelType::Poisson, SlabKernelType::Ellipse}) {
    SlabKernelBuilder b(t, 0, vec2(0.5f, 0.25f), glm::mat2(0.0f), 1);
    const SlabKernel k = b.for_slab(3);
    ASSERT_EQ(k.count, 1);
    EXPECT_EQ(k.offset(0, 1.0f, 0.0f), vec2(0.5f, 0.25f));
  }
}

TEST(ConvolutionSlabKernel, PrincipalAxesInvertRotatedCovariance) {
  const PrincipalAxes p = principal_axes(rotated_covariance(3.0f, 0.5f, 70.0f));
  EXPECT_NEAR(p.var_x, 3.0f, 1e-5f);
  EXPECT_NEAR(p.var_y, 0.5f, 1e-5f);
  EXPECT_NEAR(glm::degrees(p.angle), 70.0f, 1e-3f);
}

}  // namespace
}  // namespace penumbra

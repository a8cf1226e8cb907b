#include "penumbra/techniques/convolution/procedural_detail.h"

#include "penumbra/base/rng.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace penumbra {
namespace {

TEST(ConvolutionDetail, ImprovedNoiseIsZeroOnTheLatticeAndBounded) {
  const NoiseTable t = make_noise_table(3);
  for (int x = -3; x < 3; ++x)
    for (int y = -3; y < 3; ++y) EXPECT_EQ(improved_noise(t, vec3(float(x), float(y), 7.0f)), 0.0f);
  Pcg32 rng(5);
  float lo = 1e9f, hi = -1e9f;
  for (int i = 0; i < 20000; ++i) {
    const vec3 p(rng.next_float() * 40.0f, rng.next_float() * 40.0f, rng.next_float() * 40.0f);
    const float n = improved_noise(t, p);
    lo = std::min(lo, n);
    hi = std::max(hi, n);
    // Continuity: a tiny step changes the value by little (gradient <= ~2.5).
    EXPECT_NEAR(improved_noise(t, p + vec3(1e-3f)), n, 1e-2f);
  }
  EXPECT_GE(lo, -1.1f);
  EXPECT_LE(hi, 1.1f);
  EXPECT_LT(lo, -0.5f);  // not degenerate
  EXPECT_GT(hi, 0.5f);
}

TEST(ConvolutionDetail, FractalsFollowTheirDefinitions) {
  const NoiseTable t = make_noise_table(1);
  const vec3 p(1.3f, 2.7f, 0.4f);
  FractalParams one;
  one.octaves = 1;
  EXPECT_FLOAT_EQ(fbm(t, p, one), improved_noise(t, p));
  FractalParams two = one;
  two.octaves = 2;
  EXPECT_NEAR(fbm(t, p, two), improved_noise(t, p) + 0.5f * improved_noise(t, 2.0f * p), 1e-6f);
  // Ridged: one octave is (offset - |n|)^2.
  const float n = improved_noise(t, p);
  EXPECT_NEAR(ridged_multifractal(t, p, one), (1.0f - std::abs(n)) * (1.0f - std::abs(n)), 1e-6f);
  // Time moves the field along z.
  FractalParams later = two;
  later.time = 0.5f;
  EXPECT_NEAR(fbm(t, p, later), fbm(t, p + vec3(0.0f, 0.0f, 0.85f), two), 1e-5f);
}

}  // namespace
}  // namespace penumbra

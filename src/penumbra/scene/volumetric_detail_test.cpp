#include "penumbra/scene/volumetric_detail.h"

#include "penumbra/base/rng.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <array>
#include <set>

namespace penumbra {
namespace {

vec4 random_point4(Pcg32& rng, float scale) {
  return vec4(rng.next_float(), rng.next_float(), rng.next_float(), rng.next_float()) * scale;
}

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

TEST(ConvolutionDetail, FourDGradientsAreTheHypercubeEdges) {
  // Reading each gradient back through unit offsets: one zero component,
  // three of +-1, and all 32 different.
  std::set<std::array<int, 4>> seen;
  for (int h = 0; h < 32; ++h) {
    std::array<int, 4> g{};
    int zeros = 0;
    for (int axis = 0; axis < 4; ++axis) {
      vec4 e(0.0f);
      e[axis] = 1.0f;
      g[std::size_t(axis)] = int(noise_grad(h, e.x, e.y, e.z, e.w));
      zeros += g[std::size_t(axis)] == 0;
      EXPECT_TRUE(g[std::size_t(axis)] == 0 || std::abs(g[std::size_t(axis)]) == 1);
    }
    EXPECT_EQ(zeros, 1);
    seen.insert(g);
    EXPECT_EQ(noise_grad(h + 32, 0.3f, -0.7f, 0.2f, 0.9f), noise_grad(h, 0.3f, -0.7f, 0.2f, 0.9f));  // hash & 31
  }
  EXPECT_EQ(seen.size(), 32u);
}

// The definition written out independently: a sum over the 16 corners of the
// product of per-axis fade weights times the corner's gradient ramp.
float reference_noise4(const NoiseTable& t, vec4 p) {
  const vec4 f = glm::floor(p), d = p - f;
  float sum = 0.0f;
  for (int c = 0; c < 16; ++c) {
    const glm::ivec4 o(c & 1, (c >> 1) & 1, (c >> 2) & 1, (c >> 3) & 1);
    int hash = 0;
    for (int axis = 0; axis < 4; ++axis) hash = t.perm[std::size_t(hash + ((int(f[axis]) + o[axis]) & 255))];
    float weight = 1.0f;
    for (int axis = 0; axis < 4; ++axis) weight *= o[axis] ? noise_fade(d[axis]) : 1.0f - noise_fade(d[axis]);
    const vec4 r = d - vec4(o);
    sum += weight * noise_grad(hash, r.x, r.y, r.z, r.w);
  }
  return sum;
}

TEST(ConvolutionDetail, FourDNoiseFollowsItsDefinition) {
  const NoiseTable t = make_noise_table(8);
  Pcg32 rng(2);
  for (int i = 0; i < 2000; ++i) {
    const vec4 p = random_point4(rng, 300.0f) - vec4(150.0f);  // also negative cells and the 256 wrap
    // Same sum in another order: float rounding only.
    EXPECT_NEAR(improved_noise(t, p), reference_noise4(t, p), 1e-5f);
  }
}

TEST(ConvolutionDetail, FourDNoiseIsZeroOnTheLatticeBoundedAndContinuous) {
  const NoiseTable t = make_noise_table(3);
  for (int x = -2; x < 2; ++x)
    for (int y = -2; y < 2; ++y)
      for (int w = -2; w < 3; ++w) EXPECT_EQ(improved_noise(t, vec4(float(x), float(y), 5.0f, float(w))), 0.0f);
  Pcg32 rng(7);
  float lo = 1e9f, hi = -1e9f;
  for (int i = 0; i < 20000; ++i) {
    const vec4 p = random_point4(rng, 40.0f);
    const float n = improved_noise(t, p);
    lo = std::min(lo, n);
    hi = std::max(hi, n);
    // Continuity: per axis |dn/dx_a| <= 1.875 * 6 + 1 (the fade's slope is at
    // most 1.875, two corner ramps differ by at most 6, each ramp's slope is
    // at most 1), so the step (1e-3, 1e-3, 1e-3, 1e-3) moves it by < 0.05; a
    // seam between cells would jump by O(1).
    EXPECT_NEAR(improved_noise(t, p + vec4(1e-3f)), n, 0.05f);
  }
  EXPECT_GE(lo, -3.0f);  // the bound in volumetric_detail.h
  EXPECT_LE(hi, 3.0f);
  EXPECT_LT(lo, -0.5f);  // not degenerate
  EXPECT_GT(hi, 0.5f);
}

TEST(ConvolutionDetail, FourDNoiseChangesWithTimeOnly) {
  const NoiseTable t = make_noise_table(4);
  Pcg32 rng(11);
  int changed = 0;
  for (int i = 0; i < 200; ++i) {
    const vec3 p = vec3(random_point4(rng, 20.0f));
    // Identical up to FMA contraction, which may differ per call site.
    EXPECT_NEAR(improved_noise(t, vec4(p, 0.37f)), improved_noise(t, vec4(p, 0.37f)), 1e-7f);
    changed += std::abs(improved_noise(t, vec4(p, 0.37f)) - improved_noise(t, vec4(p, 0.87f))) > 1e-3f;
  }
  EXPECT_GT(changed, 150);
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
  // The 3D forms do not depend on time.
  FractalParams later = two;
  later.time = 0.5f;
  EXPECT_EQ(fbm(t, p, later), fbm(t, p, two));
}

TEST(ConvolutionDetail, FourDFractalsFollowTheirDefinitions) {
  const NoiseTable t = make_noise_table(6);
  const vec4 p(1.3f, 2.7f, 0.4f, 0.65f);
  FractalParams f;
  f.octaves = 3;
  f.lacunarity = 2.5f;
  f.gain = 0.4f;
  f.offset = 0.9f;
  const float n0 = improved_noise(t, p), n1 = improved_noise(t, 2.5f * p), n2 = improved_noise(t, 6.25f * p);
  EXPECT_NEAR(fbm(t, p, f), n0 + 0.4f * n1 + 0.16f * n2, 1e-5f);
  // Ridged by hand: s_i = (offset - |n_i|)^2 * w_i, w_0 = 1,
  // w_{i+1} = clamp(s_i * gain, 0, 1), sum s_i / lacunarity^i.
  const float s0 = (0.9f - std::abs(n0)) * (0.9f - std::abs(n0));
  const float w1 = std::clamp(s0 * 0.4f, 0.0f, 1.0f);
  const float s1 = (0.9f - std::abs(n1)) * (0.9f - std::abs(n1)) * w1;
  const float w2 = std::clamp(s1 * 0.4f, 0.0f, 1.0f);
  const float s2 = (0.9f - std::abs(n2)) * (0.9f - std::abs(n2)) * w2;
  EXPECT_NEAR(ridged_multifractal(t, p, f), s0 + s1 / 2.5f + s2 / 6.25f, 1e-5f);
  // Different seeds give different fields.
  EXPECT_NE(fbm(make_noise_table(7), p, f), fbm(t, p, f));
}

}  // namespace
}  // namespace penumbra

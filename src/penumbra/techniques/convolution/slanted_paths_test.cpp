#include "penumbra/techniques/convolution/slanted_paths.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace penumbra {
namespace slanted_paths_test {  // named: the test sources build as unity files
namespace {

// The depth a path over [z0, z0 + span] spends between two ends that move
// linearly along it, counted on a fine grid of the path.
float brute_force_inside(float z0, float span, float h, float g, float dh, float dg) {
  constexpr int kSteps = 200000;
  int inside = 0;
  for (int k = 0; k < kSteps; ++k) {
    const float u = (float(k) + 0.5f) / float(kSteps);
    const float z = z0 + u * span;
    if (z >= h + (u - 0.5f) * dh && z <= g + (u - 0.5f) * dg) ++inside;
  }
  return span * float(inside) / float(kSteps);
}

// Level ends give the column's covered depth; tilted ones the exact
// crossing of the linear ends, whatever their signs and sizes (a surface
// steeper than the path too).
TEST(SlantedInsideLength, MatchesTheLinearEndsExactly) {
  EXPECT_FLOAT_EQ(slanted_inside_length(0.0f, 1.0f, 0.25f, 2.0f, 0.0f, 0.0f), 0.75f);
  EXPECT_FLOAT_EQ(slanted_inside_length(0.0f, 1.0f, -1.0f, 0.5f, 0.0f, 0.0f), 0.5f);
  EXPECT_FLOAT_EQ(slanted_inside_length(0.0f, 1.0f, 2.0f, 3.0f, 0.0f, 0.0f), 0.0f);
  EXPECT_FLOAT_EQ(slanted_inside_length(0.0f, 1.0f, -1.0f, 3.0f, 0.0f, 0.0f), 1.0f);
  // The entering surface at the slab's middle, sinking as fast as the path:
  // the path runs along it, just in front (never inside) or just behind
  // (inside all along), where the column is inside for half the slab ...
  EXPECT_FLOAT_EQ(slanted_inside_length(0.0f, 1.0f, 0.5f + 1e-4f, 9.0f, 1.0f, 0.0f), 0.0f);
  EXPECT_FLOAT_EQ(slanted_inside_length(0.0f, 1.0f, 0.5f - 1e-4f, 9.0f, 1.0f, 0.0f), 1.0f);
  // ... rising as fast: they meet at the middle.
  EXPECT_NEAR(slanted_inside_length(0.0f, 1.0f, 0.5f, 9.0f, -1.0f, 0.0f), 0.5f, 1e-6f);
  EXPECT_NEAR(slanted_inside_length(0.0f, 1.0f, 0.7f, 9.0f, -1.0f, 0.0f), 0.4f, 1e-6f);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> depth(-1.5f, 2.5f), change(-3.0f, 3.0f);
  for (int trial = 0; trial < 300; ++trial) {
    const float h = depth(rng), g = h + std::abs(depth(rng)), dh = change(rng), dg = change(rng);
    const float span = 0.5f + 0.5f * std::abs(change(rng));
    const float exact = slanted_inside_length(0.25f, span, h, g, dh, dg);
    EXPECT_NEAR(exact, brute_force_inside(0.25f, span, h, g, dh, dg), 2e-4f * span)
        << "h " << h << " g " << g << " dh " << dh << " dg " << dg << " span " << span;
  }
}

// A tilted plane of medium, depth >= a x + b y + c, as one run per pixel:
// the depth a straight path spends inside it is exact (the run's ends are
// read on the pixel grid and are planes), wherever the path crosses the
// pixel's ray and however far it travels sideways.
TEST(SurfaceRuns, PathsThroughATiltedPlaneAreExact) {
  constexpr int kSize = 16;
  const float a = 0.3f, b = -0.2f, c = 5.0f, far = 1000.0f;
  std::vector<vec2> runs(std::size_t(kSize * kSize));
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) {
      runs[std::size_t(x + kSize * y)] = vec2(a * (float(x) + 0.5f) + b * (float(y) + 0.5f) + c, far);
    }
  }
  SurfaceRuns surface;
  surface.from_intervals(runs, kSize, kSize);
  const float e = 1.0f;
  int checked = 0;
  for (float z0 : {4.0f, 5.3f, 6.0f, 7.5f}) {
    surface.enter_slab(z0, e);
    for (int y : {0, 7, 15}) {
      for (int x : {0, 8, 15}) {
        for (vec2 d : {vec2(1.5f, 0.0f), vec2(-0.7f, 0.9f), vec2(0.0f, 0.0f)}) {
          for (float through : {z0, z0 + 0.5f, z0 + e}) {
            const std::size_t i = std::size_t(x + kSize * y);
            const float to = z0 + e;
            // The path at depth z is at pixel (x, y) + (z - through) d.
            const float h = runs[i].x, slope = a * d.x + b * d.y;
            const float expected =
                brute_force_inside(z0, e, h + (z0 + 0.5f * e - through) * slope, far, e * slope, 0.0f);
            EXPECT_NEAR(surface.inside(i, d, z0, through, to), expected, 1e-3f)
                << "pixel " << x << ", " << y << " z0 " << z0 << " through " << through;
            ++checked;
          }
        }
      }
    }
  }
  EXPECT_EQ(checked, 4 * 9 * 3 * 3);
}

// Where a pixel's ray meets no medium there is nothing inside; its run's
// neighbours still give the gradients (one-sided at the run's edge).
TEST(SurfaceRuns, NoRunNothingInsideAndOneSidedAtTheEdge) {
  constexpr int kSize = 4;
  std::vector<vec2> runs(std::size_t(kSize * kSize), vec2(1.0f, 0.0f));  // none
  for (int x = 1; x < kSize; ++x) runs[std::size_t(x + kSize)] = vec2(2.0f + 0.5f * float(x), 100.0f);
  SurfaceRuns surface;
  surface.from_intervals(runs, kSize, kSize);
  surface.enter_slab(3.0f, 1.0f);
  EXPECT_FALSE(surface.any(0));
  EXPECT_EQ(surface.inside(0, vec2(1.0f, 0.0f), 3.0f, 3.5f, 4.0f), 0.0f);
  // Pixel (1, 1): h = 2.5, its slope one-sided toward +x, 0.5 per pixel.
  // A path moving 2 pixels per unit depth toward +x, crossing the pixel's ray
  // at the slab's back (depth 4), meets the surface at depth 2.5 + (z - 4):
  // behind it all along.
  EXPECT_NEAR(surface.inside(std::size_t(1 + kSize), vec2(2.0f, 0.0f), 3.0f, 4.0f, 4.0f), 1.0f, 1e-6f);
  // Moving 4 pixels per unit depth toward -x, the surface lies at
  // 2.5 - 2 (z - 4) along the path: the path is behind it from z = 3.5 on.
  EXPECT_NEAR(surface.inside(std::size_t(1 + kSize), vec2(-4.0f, 0.0f), 3.0f, 4.0f, 4.0f), 0.5f, 1e-5f);
}

}  // namespace
}  // namespace slanted_paths_test
}  // namespace penumbra

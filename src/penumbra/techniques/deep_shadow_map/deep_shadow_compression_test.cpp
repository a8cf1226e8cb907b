// The deep shadow map's compression against brute force: the stored nodes
// stay within the tolerance they report at every breakpoint of random
// transmittance functions, simple shapes take the nodes they should, more
// nodes never need a looser tolerance, and the tail is exact.
#include "penumbra/base/rng.h"
#include "penumbra/techniques/deep_shadow_map/deep_shadow_compression.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

namespace penumbra {
namespace {

struct Breakpoint {
  float depth;
  vec3 value;
};

// A random non-increasing per-channel function: flat stretches, gentle
// slopes and sharp drops (surfaces), as light rays through a volume give.
std::vector<Breakpoint> random_transmittance(Pcg32& rng) {
  std::vector<Breakpoint> f{{2.0f + 5.0f * rng.next_float(), vec3(1.0f)}};
  vec3 t(1.0f);
  float z = f[0].depth;
  const int n = 20 + int(rng.next_uint() % 200);
  for (int i = 0; i < n; ++i) {
    z += 0.5f;
    const float kind = rng.next_float();
    float alpha = 0.0f;
    if (kind > 0.95f) {
      alpha = 0.3f + 0.7f * rng.next_float();  // a surface
    } else if (kind > 0.5f) {
      alpha = 0.03f * rng.next_float();  // haze
    }
    const vec3 color(rng.next_float(), rng.next_float(), rng.next_float());
    t *= 1.0f - alpha * (1.0f - color);
    f.push_back({z, t});
  }
  return f;
}

vec3 evaluate(const DeepShadowNodes& c, float z) {
  std::vector<float> texel;
  for (int k = 0; k < c.count; ++k) {
    const DeepShadowNode& n = c.nodes[k];
    texel.insert(texel.end(), {n.depth, n.transmittance.r, n.transmittance.g, n.transmittance.b});
  }
  if (texel.empty()) texel = {kInfinity, 1.0f, 1.0f, 1.0f};
  return evaluate_deep_shadow(texel.data(), std::max(c.count, 1), z);
}

DeepShadowNodes compress(DeepShadowCompressor& compressor, const std::vector<Breakpoint>& f) {
  for (const Breakpoint& b : f) compressor.add(b.depth, b.value);
  return compressor.finish();
}

float max_error(const std::vector<Breakpoint>& f, const DeepShadowNodes& c) {
  float worst = 0.0f;
  for (const Breakpoint& b : f) worst = std::max(worst, max_component(glm::abs(evaluate(c, b.depth) - b.value)));
  // Before the first and after the last breakpoint the function is constant.
  worst = std::max(worst, max_component(glm::abs(evaluate(c, 0.0f) - vec3(1.0f))));
  worst = std::max(worst, max_component(glm::abs(evaluate(c, 1e6f) - f.back().value)));
  return worst;
}

TEST(DeepShadowCompression, NodesStayWithinTheToleranceTheyReport) {
  Pcg32 rng(42);
  int fitted_at_base = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const std::vector<Breakpoint> f = random_transmittance(rng);
    float previous_bound = kInfinity;
    for (int nodes : {2, 3, 4, 8, 16}) {
      DeepShadowCompressor compressor(0.01f, nodes);
      const DeepShadowNodes c = compress(compressor, f);
      ASSERT_LE(c.count, nodes);
      for (int k = 1; k < c.count; ++k) ASSERT_GT(c.nodes[k].depth, c.nodes[k - 1].depth);
      if (c.overflowed) continue;  // no bound claimed
      const float bound = c.tolerance;
      // Both functions are linear between breakpoints, so the breakpoints bound the error everywhere.
      ASSERT_LE(max_error(f, c), bound * (1.0f + 1e-4f) + 1e-6f) << "trial " << trial << ", " << nodes << " nodes";
      // More nodes never need a larger level; the bound is the level's tolerance plus the tail's change, which
      // is at most that tolerance, so it can grow by at most 2x (the tail fix trades a little bound for an
      // exact tail).
      EXPECT_LE(bound, 2.0f * previous_bound) << "more nodes must not loosen the bound beyond the tail's change";
      previous_bound = bound;
      if (nodes == 16 && bound == 0.01f) ++fitted_at_base;
    }
  }
  EXPECT_GT(fitted_at_base, 150) << "16 nodes should meet the base tolerance on most functions";
}

TEST(DeepShadowCompression, SimpleShapesTakeFewNodes) {
  // No attenuation at all: no node (the function is 1 everywhere).
  {
    DeepShadowCompressor compressor(0.01f, 3);
    std::vector<Breakpoint> f;
    for (int i = 0; i < 10; ++i) f.push_back({float(i), vec3(1.0f)});
    EXPECT_EQ(compress(compressor, f).count, 0);
  }
  // One opaque surface after a stretch of empty space: 2 nodes, (10, 1) and
  // (11, 0), at the base tolerance.
  {
    DeepShadowCompressor compressor(0.01f, 2);
    std::vector<Breakpoint> f{{0.0f, vec3(1.0f)}, {10.0f, vec3(1.0f)}, {10.5f, vec3(0.5f)}, {11.0f, vec3(0.0f)}};
    for (int i = 0; i < 20; ++i) f.push_back({11.5f + float(i), vec3(0.0f)});
    const DeepShadowNodes c = compress(compressor, f);
    ASSERT_FALSE(c.overflowed);
    EXPECT_EQ(c.tolerance, 0.01f);
    ASSERT_EQ(c.count, 2);
    EXPECT_FLOAT_EQ(c.nodes[0].depth, 10.0f);
    EXPECT_NEAR(c.nodes[1].depth, 11.0f, 1e-6f);
    EXPECT_LT(max_component(glm::abs(c.nodes[1].transmittance)), 0.02f);
  }
  // A linear ramp: its two ends.
  {
    DeepShadowCompressor compressor(0.001f, 2);
    std::vector<Breakpoint> f;
    for (int i = 0; i <= 50; ++i) f.push_back({float(i), vec3(1.0f - 0.01f * float(i))});
    const DeepShadowNodes c = compress(compressor, f);
    ASSERT_FALSE(c.overflowed);
    EXPECT_EQ(c.tolerance, 0.001f);
    EXPECT_EQ(c.count, 2);
  }
}

// A translucent shell around an opaque core (the ray of scenes/shell-point
// through the core): a smooth drop, a flat gap, a sharp drop to 0. Three
// nodes cannot follow it within 0.01, so the tolerance is raised; the tail,
// which a floor behind the volume reads, still comes out exactly 0 (it was
// 0.115 before the tail was made exact) and the reported bound covers the
// whole function.
TEST(DeepShadowCompression, TailIsExactWhenTheToleranceIsRaised) {
  std::vector<Breakpoint> f;
  for (int i = 0; i <= 20; ++i) f.push_back({float(i), vec3(1.0f)});
  float t = 1.0f;
  for (int i = 1; i <= 20; ++i) {
    t *= 0.959f;  // 0.43 after 20 steps
    f.push_back({20.0f + 0.5f * float(i), vec3(t)});
  }
  for (int i = 1; i <= 24; ++i) f.push_back({30.0f + 0.5f * float(i), vec3(t)});
  f.push_back({42.5f, vec3(0.0f)});
  for (int i = 1; i <= 10; ++i) f.push_back({42.5f + float(i), vec3(0.0f)});
  DeepShadowCompressor compressor(0.01f, 3);
  const DeepShadowNodes c = compress(compressor, f);
  ASSERT_FALSE(c.overflowed);
  EXPECT_GT(c.tolerance, 0.05f) << "three nodes should not fit this function closely";
  EXPECT_LE(c.count, 3);
  EXPECT_NEAR(max_component(evaluate(c, 1e6f)), 0.0f, 1e-6f);
  EXPECT_LE(max_error(f, c), c.tolerance * (1.0f + 1e-4f) + 1e-6f);
  EXPECT_NEAR(max_component(evaluate(c, 5.0f)), 1.0f, 1e-6f) << "in front of the attenuation: lit";
}

// When nothing fits, the last level slides its last node to the end, so the
// far tail is exact.
TEST(DeepShadowCompression, OverflowKeepsTheTailValue) {
  DeepShadowCompressor compressor(0.001f, 2);
  float z = 0.0f;
  vec3 t(1.0f);
  compressor.add(z, t);
  for (int surface = 0; surface < 6; ++surface) {
    z += 5.0f;
    compressor.add(z, t);
    z += 0.5f;
    t *= 0.5f;
    compressor.add(z, t);
  }
  compressor.add(z + 10.0f, t);
  const DeepShadowNodes c = compressor.finish();
  EXPECT_TRUE(c.overflowed);
  EXPECT_EQ(c.count, 2);
  EXPECT_FLOAT_EQ(c.nodes[1].depth, z + 10.0f);
  EXPECT_NEAR(c.nodes[1].transmittance.r, t.r, 1e-6f);
}

}  // namespace
}  // namespace penumbra

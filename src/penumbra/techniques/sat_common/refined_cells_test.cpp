// Refined cells (refined_cells.h) against brute force on an analytic optical
// depth with a lit surface: tau = g x + k max(0, n.p - d), a shallow ramp
// in front of the plane n.p = d (a penumbra the cache reads well, though its
// cells' texels differ by more than the tolerance) and growing steeply
// behind it, as inside a lit material.
#include "penumbra/techniques/sat_common/refined_cells.h"

#include "penumbra/base/error.h"
#include "penumbra/base/memory_budget.h"
#include "penumbra/base/rng.h"
#include "penumbra/techniques/sat_common/visibility_cache.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace penumbra {
namespace {

struct SurfaceDepth {
  vec3 n = glm::normalize(vec3(0.3f, 0.5f, 0.8f));
  float d = 11.0f;
  float g = 0.07f;  // per world unit along x
  float k = 1.5f;   // per world unit behind the surface
  float operator()(vec3 p) const { return g * p.x + k * std::max(0.0f, glm::dot(n, p) - d); }
  float visibility(vec3 p) const { return std::exp(-(*this)(p)); }
};

constexpr float kTolerance = 0.1f, kProbeTolerance = 0.01f;
constexpr int kRefine = 3;

struct Fixture {
  SurfaceDepth tau;
  Box3 box{vec3(0.0f), vec3(18.0f)};
  Volume cache = build_visibility_cache(box, ivec3(10), [&](vec3 p) { return tau.visibility(p); });
  RefinedCells cells;
  Fixture() { cells.build(cache, kTolerance, kProbeTolerance, kRefine, tau); }

  // Corner texels of cell c, and the cache's trilinear read at f in [0, 1]^3.
  float corner(ivec3 c, int k) const {
    const ivec3 q = c + ivec3(k & 1, (k >> 1) & 1, (k >> 2) & 1);
    return cache.frame_as<float>(0)[q.x + 10 * (q.y + 10 * q.z)];
  }
  float trilinear(ivec3 c, vec3 f) const {
    float v = 0.0f;
    for (int k = 0; k < 8; ++k) {
      v += corner(c, k) * (k & 1 ? f.x : 1.0f - f.x) * (k & 2 ? f.y : 1.0f - f.y) * (k & 4 ? f.z : 1.0f - f.z);
    }
    return v;
  }
  vec3 world(ivec3 c, vec3 f) const { return cache.view().world_from_index(vec3(c) + f); }
};

// A cell gets a brick exactly when its texels differ by more than the
// tolerance and the cache misses a probe (centre or a face centre); at its
// texels (sub-cell centres) a brick reads the depth there, and in cells
// the surface does not cross it reads the linear depth everywhere (the
// half sub-cells at the faces extrapolate).
TEST(RefinedCells, BricksMatchBruteForce) {
  const Fixture fx;
  const RefinedCellsView view = fx.cells.view();
  const VolumeView cache = fx.cache.view();
  ASSERT_EQ(view.refine, kRefine);
  std::size_t expected = 0, rough = 0;
  double worst_texel = 0.0, worst_linear = 0.0, crossing = 0.0, crossing_cache = 0.0;
  int crossing_points = 0;
  Pcg32 rng(3);
  for (int z = 0; z < 9; ++z)
    for (int y = 0; y < 9; ++y)
      for (int x = 0; x < 9; ++x) {
        const ivec3 c(x, y, z);
        float lo = 1.0f, hi = 0.0f;
        for (int k = 0; k < 8; ++k) {
          lo = std::min(lo, fx.corner(c, k));
          hi = std::max(hi, fx.corner(c, k));
        }
        bool missed = false;
        for (const vec3& f : {vec3(0.5f), vec3(0.0f, 0.5f, 0.5f), vec3(1.0f, 0.5f, 0.5f), vec3(0.5f, 0.0f, 0.5f),
                             vec3(0.5f, 1.0f, 0.5f), vec3(0.5f, 0.5f, 0.0f), vec3(0.5f, 0.5f, 1.0f)}) {
          missed = missed || std::abs(fx.trilinear(c, f) - fx.tau.visibility(fx.world(c, f))) > kProbeTolerance;
        }
        rough += hi - lo > kTolerance ? 1 : 0;
        const bool brick = hi - lo > kTolerance && missed;
        expected += brick ? 1 : 0;
        float value = -1.0f;
        ASSERT_EQ(view.sample(cache, fx.world(c, vec3(0.5f)), value), brick) << x << " " << y << " " << z;
        if (!brick) continue;
        for (int k = 0; k < kRefine * kRefine * kRefine; ++k) {
          const vec3 f = (vec3(k % kRefine, k / kRefine % kRefine, k / (kRefine * kRefine)) + 0.5f) / float(kRefine);
          ASSERT_TRUE(view.sample(cache, fx.world(c, f), value));
          worst_texel = std::max(worst_texel, double(std::abs(value - fx.tau.visibility(fx.world(c, f)))));
        }
        // The surface crosses the cell where its corners lie on both sides.
        float s_lo = 1e9f, s_hi = -1e9f;
        for (int k = 0; k < 8; ++k) {
          const float s = glm::dot(fx.tau.n, fx.world(c, vec3(k & 1, (k >> 1) & 1, (k >> 2) & 1))) - fx.tau.d;
          s_lo = std::min(s_lo, s);
          s_hi = std::max(s_hi, s);
        }
        const bool crosses = s_lo < 0.0f && s_hi > 0.0f;
        for (int i = 0; i < 200; ++i) {
          const vec3 f(rng.next_float(), rng.next_float(), rng.next_float());
          ASSERT_TRUE(view.sample(cache, fx.world(c, f), value));
          const float truth = fx.tau.visibility(fx.world(c, f));
          if (!crosses) {
            worst_linear = std::max(worst_linear, double(std::abs(value - truth)));
            continue;
          }
          crossing += std::abs(value - truth);
          crossing_cache += std::abs(fx.trilinear(c, f) - truth);
          ++crossing_points;
        }
      }
  crossing /= crossing_points;
  crossing_cache /= crossing_points;
  std::printf("[refined cells] %zu bricks of %zu rough cells; worst |dV| at texels %.2e, in linear cells %.2e; "
              "mean |dV| where the surface crosses %.4f (the cache there: %.4f)\n",
              expected, rough, worst_texel, worst_linear, crossing, crossing_cache);
  EXPECT_EQ(fx.cells.brick_count(), expected);
  EXPECT_GT(expected, 20u);
  EXPECT_LT(expected, rough - 20) << "the probes leave out rough cells the cache reads well";
  EXPECT_LT(worst_texel, 2e-4);   // 16-bit depth: 1.3e-4 relative
  EXPECT_LT(worst_linear, 5e-4);  // exact up to the rounding
  // Across the surface the depth's kink is interpolated over one sub-cell
  // instead of the visibility's over the cell.
  EXPECT_LT(crossing, 0.35 * crossing_cache);  // measured 0.16
}

// Bytes: a 4-byte first index and an 8-byte mask per block of 4^3 cells,
// and refine^3 16-bit texels per brick; bricks that do not fit the memory
// budget are a typed error before anything is allocated.
TEST(RefinedCells, BytesAndMemoryBudget) {
  Fixture fx;
  const std::uint64_t blocks = 3 * 3 * 3;  // 9 cells per axis in blocks of 4
  EXPECT_EQ(fx.cells.bytes(), blocks * 12 + fx.cells.brick_count() * kRefine * kRefine * kRefine * 2);
  RefinedCells finer;
  finer.build(fx.cache, kTolerance, kProbeTolerance, 8, fx.tau);
  EXPECT_EQ(finer.brick_count(), fx.cells.brick_count());
  EXPECT_EQ(finer.bytes(), blocks * 12 + finer.brick_count() * 512 * 2);
  finer.clear();
  EXPECT_EQ(finer.bytes(), 0u);
  float value;
  EXPECT_FALSE(finer.view().sample(fx.cache.view(), vec3(9.0f), value));
  const std::uint64_t budget = memory_budget_bytes();
  set_memory_budget_bytes(fx.cells.brick_count() * 512 * 2 - 1);
  EXPECT_THROW(finer.build(fx.cache, kTolerance, kProbeTolerance, 8, fx.tau), OutOfMemoryBudget);
  set_memory_budget_bytes(budget);
}

}  // namespace
}  // namespace penumbra

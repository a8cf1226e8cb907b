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
#include <type_traits>

namespace penumbra {
namespace {

// The view points into the object's own vectors: a vector of them (one per
// light) must move them when it grows, never copy them (a copy's view read the
// original's freed bricks).
static_assert(std::is_nothrow_move_constructible_v<RefinedCells>);
static_assert(!std::is_copy_constructible_v<RefinedCells>);

struct SurfaceDepth {
  vec3 n = glm::normalize(vec3(0.3f, 0.5f, 0.8f));
  float d = 11.0f;
  float g = 0.07f;  // per world unit along x
  float k = 1.5f;   // per world unit behind the surface
  float operator()(vec3 p) const { return g * p.x + k * std::max(0.0f, glm::dot(n, p) - d); }
  float visibility(vec3 p) const { return std::exp(-(*this)(p)); }
};

constexpr float kTolerance = 0.1f, kProbeTolerance = 0.01f;  // the probe's on the cube root
constexpr int kRefine = 4;                                      // bricks of 2^3 or 4^3 texels

double cbrt_miss(float read, float truth) {
  return std::abs(std::cbrt(double(std::max(read, 0.0f))) - std::cbrt(double(truth)));
}
bool misses(float read, float truth) {
  return std::abs(std::cbrt(std::max(read, 0.0f)) - std::cbrt(truth)) > kProbeTolerance;
}

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

  // Brute force: a brick of n^3 texels for cell c, from the depth at the
  // sub-cell centres, coded as 255 exp(-depth / 3).
  std::vector<std::uint8_t> brick(ivec3 c, int n) const {
    std::vector<std::uint8_t> t(std::size_t(n * n * n));
    for (int k = 0; k < n * n * n; ++k) {
      const vec3 f = (vec3(k % n, k / n % n, k / (n * n)) + 0.5f) / float(n);
      t[std::size_t(k)] = std::uint8_t(std::lround(255.0 * std::exp(-std::max(tau(world(c, f)), 0.0f) / 3.0)));
    }
    return t;
  }
  // Whether a brick of n^3 misses the visibility halfway between two of
  // its texels or at a face's centre.
  bool brick_misses(ivec3 c, int n) const {
    const std::vector<std::uint8_t> t = brick(c, n);
    std::vector<vec3> checks;
    for (int z = 1; z < n; ++z)
      for (int y = 1; y < n; ++y)
        for (int x = 1; x < n; ++x) checks.push_back(vec3(x, y, z) / float(n));
    for (int axis = 0; axis < 3; ++axis)
      for (const float side : {0.0f, 1.0f}) {
        vec3 f(0.5f);
        f[axis] = side;
        checks.push_back(f);
      }
    for (const vec3& f : checks) {
      if (misses(std::exp(-brick_depth(t.data(), n, f, brick_depth_table())), tau.visibility(world(c, f)))) {
        return true;
      }
    }
    return false;
  }
};

// The level (brick resolution) cell c has in `view`, or 0.
int brick_resolution(const RefinedCellsView& view, ivec3 c) {
  const ivec3 b = c >> 2;
  const int block = b.x + view.blocks.x * (b.y + view.blocks.y * b.z);
  const int bit = (c.x & 3) + 4 * (c.y & 3) + 16 * (c.z & 3);
  int found = 0;
  for (int l = 0; l < view.levels; ++l) {
    if (view.level[l].bricks == 0) continue;
    if ((view.level[l].block_mask[block] >> bit) & 1u) {
      EXPECT_EQ(found, 0) << "a cell with two bricks";
      found = view.level[l].refine;
    }
  }
  return found;
}

// A cell gets a brick exactly when its texels differ by more than the
// tolerance and the cache misses a probe (centre or a face centre) on the
// cube root of the visibility; the brick is the coarsest (2^3, else 4^3)
// whose read meets the visibility halfway between its texels and at the
// faces' centres. At its texels (sub-cell centres) a brick reads the depth
// there, and in cells the surface does not cross it reads the linear depth
// everywhere (the half sub-cells at the faces extrapolate).
TEST(RefinedCells, BricksMatchBruteForce) {
  const Fixture fx;
  const RefinedCellsView view = fx.cells.view();
  const VolumeView cache = fx.cache.view();
  ASSERT_EQ(view.levels, 2);
  ASSERT_EQ(view.level[0].refine, 2);
  ASSERT_EQ(view.level[1].refine, kRefine);
  std::size_t expected = 0, rough = 0, coarse = 0;
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
          missed = missed || misses(fx.trilinear(c, f), fx.tau.visibility(fx.world(c, f)));
        }
        rough += hi - lo > kTolerance ? 1 : 0;
        const bool brick = hi - lo > kTolerance && missed;
        expected += brick ? 1 : 0;
        float value = -1.0f;
        ASSERT_EQ(view.sample(cache, fx.world(c, vec3(0.5f)), value), brick) << x << " " << y << " " << z;
        if (!brick) {
          ASSERT_EQ(brick_resolution(view, c), 0);
          continue;
        }
        const int n = fx.brick_misses(c, 2) ? kRefine : 2;
        ASSERT_EQ(brick_resolution(view, c), n) << x << " " << y << " " << z;
        coarse += n == 2 ? 1 : 0;
        for (int k = 0; k < n * n * n; ++k) {
          const vec3 f = (vec3(k % n, k / n % n, k / (n * n)) + 0.5f) / float(n);
          ASSERT_TRUE(view.sample(cache, fx.world(c, f), value));
          worst_texel = std::max(worst_texel, cbrt_miss(value, fx.tau.visibility(fx.world(c, f))));
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
            worst_linear = std::max(worst_linear, cbrt_miss(value, truth));
            continue;
          }
          crossing += std::abs(value - truth);
          crossing_cache += std::abs(fx.trilinear(c, f) - truth);
          ++crossing_points;
        }
      }
  crossing /= crossing_points;
  crossing_cache /= crossing_points;
  std::printf("[refined cells] %zu bricks (%zu of 2^3) of %zu rough cells; worst |d cbrt V| at texels %.2e, in "
              "linear cells %.2e; mean |dV| where the surface crosses %.4f (the cache there: %.4f)\n",
              expected, coarse, rough, worst_texel, worst_linear, crossing, crossing_cache);
  EXPECT_EQ(fx.cells.brick_count(), expected);
  EXPECT_EQ(fx.cells.brick_count(0), coarse);
  EXPECT_GT(coarse, 20u) << "cells a plane surface does not cross need no more than 2^3";
  EXPECT_GT(expected - coarse, 20u) << "cells it crosses need more";
  EXPECT_LT(expected, rough - 20) << "the probes leave out rough cells the cache reads well";
  // The codes round the cube root of the visibility to 1/255: at most half
  // a step at the texels. Between them a lit point's read also carries a
  // deeper texel's rounding, which is larger in depth (and doubled where the
  // half sub-cells at the faces extrapolate): measured 1.9 steps.
  EXPECT_LT(worst_texel, 0.5 / 255.0 + 1e-5);
  EXPECT_LT(worst_linear, 2.5 / 255.0);
  // Across the surface the depth's kink is interpolated over one sub-cell
  // instead of the visibility's over the cell.
  EXPECT_LT(crossing, 0.2 * crossing_cache);  // measured 0.10
}

// Bytes: per level with bricks a 4-byte first index and an 8-byte mask per
// block of 4^3 cells, and n^3 8-bit texels per brick; bricks that do not
// fit the memory budget are a typed error before anything is allocated.
TEST(RefinedCells, BytesAndMemoryBudget) {
  Fixture fx;
  const std::uint64_t blocks = 3 * 3 * 3;  // 9 cells per axis in blocks of 4
  EXPECT_EQ(fx.cells.bytes(), 2 * blocks * 12 + fx.cells.brick_count(0) * 8 + fx.cells.brick_count(1) * 64);
  RefinedCells finer;
  finer.build(fx.cache, kTolerance, kProbeTolerance, 8, fx.tau);  // 2, 4, 6 and 8
  ASSERT_EQ(finer.view().levels, 4);
  EXPECT_EQ(finer.brick_count(), fx.cells.brick_count());
  EXPECT_EQ(finer.brick_count(0), fx.cells.brick_count(0));
  std::uint64_t bytes = 0;
  for (int l = 0; l < 4; ++l) {
    const std::uint64_t n = 2 * std::uint64_t(l + 1);
    if (finer.brick_count(l) > 0) bytes += blocks * 12 + finer.brick_count(l) * n * n * n;
  }
  EXPECT_EQ(finer.bytes(), bytes);
  finer.clear();
  EXPECT_EQ(finer.bytes(), 0u);
  float value;
  EXPECT_FALSE(finer.view().sample(fx.cache.view(), vec3(9.0f), value));
  const std::uint64_t budget = memory_budget_bytes();
  set_memory_budget_bytes(fx.cells.brick_count(1) * 64 - 1);
  EXPECT_THROW(finer.build(fx.cache, kTolerance, kProbeTolerance, 4, fx.tau), OutOfMemoryBudget);
  set_memory_budget_bytes(budget);
}

}  // namespace
}  // namespace penumbra

#include "penumbra/base/error.h"
#include "penumbra/base/memory_budget.h"
#include "penumbra/base/numeric_cast.h"
#include "penumbra/base/parallel.h"
#include "penumbra/base/ray.h"
#include "penumbra/base/rng.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <vector>

namespace penumbra {
namespace {

TEST(Ray, BoxIntervalMatchesHandComputedChord) {
  const Box3 box{vec3(-1.0f), vec3(1.0f)};
  const Interval i = intersect_box(Ray{vec3(-5.0f, 0.0f, 0.0f), vec3(1.0f, 0.0f, 0.0f)}, box, 0.0f, kInfinity);
  EXPECT_FLOAT_EQ(i.t0, 4.0f);
  EXPECT_FLOAT_EQ(i.t1, 6.0f);
}

TEST(Ray, AxisParallelRayOnTheBoxFaceHasNoNaN) {
  const Box3 box{vec3(0.0f), vec3(1.0f)};
  // Origin exactly on the lower y and z faces, direction along x.
  const Interval i = intersect_box(Ray{vec3(-1.0f, 0.0f, 0.0f), vec3(1.0f, 0.0f, 0.0f)}, box, 0.0f, kInfinity);
  EXPECT_FALSE(i.empty());
  EXPECT_FLOAT_EQ(i.t0, 1.0f);
  EXPECT_FLOAT_EQ(i.t1, 2.0f);
  const Interval miss = intersect_box(Ray{vec3(-1.0f, 2.0f, 0.5f), vec3(1.0f, 0.0f, 0.0f)}, box, 0.0f, kInfinity);
  EXPECT_TRUE(miss.empty());
}

TEST(Ray, RayStartingInsideTheBoxStartsAtTMin) {
  const Box3 box{vec3(-1.0f), vec3(1.0f)};
  const Interval i = intersect_box(Ray{vec3(0.0f), glm::normalize(vec3(1.0f, 1.0f, 0.0f))}, box, 0.0f, kInfinity);
  EXPECT_FLOAT_EQ(i.t0, 0.0f);
  EXPECT_NEAR(i.t1, std::sqrt(2.0f), 1e-6f);
}

TEST(Ray, ClipIntervalKeepsThePositiveHalfSpace) {
  const vec4 plane(0.0f, 0.0f, 1.0f, -0.25f);  // keeps z >= 0.25
  const Ray ray{vec3(0.0f, 0.0f, -1.0f), vec3(0.0f, 0.0f, 1.0f)};
  const Interval i = clip_interval(ray, &plane, 1, Interval{0.0f, 2.0f});
  EXPECT_FLOAT_EQ(i.t0, 1.25f);
  EXPECT_FLOAT_EQ(i.t1, 2.0f);
  EXPECT_TRUE(inside_clip_planes(vec3(0.0f, 0.0f, 0.3f), &plane, 1));
  EXPECT_FALSE(inside_clip_planes(vec3(0.0f, 0.0f, 0.2f), &plane, 1));
  // A ray parallel to the plane on its clipped side is empty.
  EXPECT_TRUE(clip_interval(Ray{vec3(0.0f), vec3(1.0f, 0.0f, 0.0f)}, &plane, 1, Interval{0.0f, 1.0f}).empty());
}

TEST(Math, ExpNonpositiveMatchesStdExp) {
  float worst = 0.0f;
  for (float x = 0.0f; x > -86.0f; x -= 0.0137f) {
    const float expected = std::exp(x);
    worst = std::max(worst, std::abs(exp_nonpositive(x) - expected) / expected);
  }
  EXPECT_LT(worst, 3e-7f);
  EXPECT_EQ(exp_nonpositive(0.0f), 1.0f);
  EXPECT_EQ(exp_nonpositive(-100.0f), 0.0f);
  EXPECT_EQ(exp_nonpositive(-std::numeric_limits<float>::infinity()), 0.0f);
  EXPECT_EQ(exp_nonpositive(std::numeric_limits<float>::quiet_NaN()), 0.0f);
}

TEST(Math, LogPositiveMatchesStdLog) {
  // Over many binades and both sides of the sqrt(2) mantissa split.
  double worst = 0.0;
  for (float x = 1e-30f; x < 1e30f; x *= 1.0137f) {
    const double expected = std::log(double(x));
    worst = std::max(worst, std::abs(log_positive(x) - expected) / std::max(1.0, std::abs(expected)));
  }
  EXPECT_LT(worst, 1e-6);
  EXPECT_EQ(log_positive(1.0f), 0.0f);
}

TEST(Math, Log2AndExp2MatchStd) {
  double worst_log = 0.0, worst_exp = 0.0;
  for (float x = 1e-20f; x < 1e20f; x *= 1.0137f) {
    const double expected = std::log2(double(x));
    worst_log = std::max(worst_log, std::abs(log2_positive(x) - expected) / std::max(1.0, std::abs(expected)));
  }
  for (float x = 0.0f; x < 100.0f; x += 0.0173f) {
    const double expected = std::exp2(double(x));
    worst_exp = std::max(worst_exp, std::abs(exp2_nonnegative(x) - expected) / expected);
  }
  EXPECT_LT(worst_log, 1e-6);
  EXPECT_LT(worst_exp, 5e-7);
  // Powers of two are exact both ways (occlusion-map's whole pyramid levels).
  for (int e = -20; e <= 20; ++e) EXPECT_EQ(log2_positive(std::ldexp(1.0f, e)), float(e));
  for (int e = 0; e <= 20; ++e) EXPECT_EQ(exp2_nonnegative(float(e)), std::ldexp(1.0f, e));
}

TEST(Math, ErfcLanesMatchesStdErfc) {
  // Relative error up to 4 (where occlusion-map uses it), and beyond, where
  // float's rounding of x^2 in the exponent sets it (about x^2 6e-8).
  double worst = 0.0, worst_tail = 0.0;
  for (float x = -6.0f; x < 9.0f; x += 0.00731f) {
    const double expected = std::erfc(double(x));
    const double error = std::abs(erfc_lanes(x) - expected) / expected;
    (x <= 4.0f ? worst : worst_tail) = std::max(x <= 4.0f ? worst : worst_tail, error);
  }
  std::printf("[math] erfc_lanes worst relative error %.2e to 4, %.2e beyond\n", worst, worst_tail);
  EXPECT_LT(worst, 2e-6);
  EXPECT_LT(worst_tail, 8e-6);
  EXPECT_EQ(erfc_lanes(-20.0f), 2.0f);
  EXPECT_EQ(erfc_lanes(20.0f), 0.0f);
}

TEST(Math, PowUnitMatchesStdPowForHighlights) {
  // Whole shininess takes repeated squaring, the rest exp(s ln x).
  for (float s : {1.0f, 2.0f, 5.0f, 20.0f, 128.0f, 255.0f, 256.0f, 0.5f, 7.5f, 33.3f, 300.0f}) {
    double worst = 0.0;
    for (int i = 1; i <= 1000; ++i) {
      const float x = float(i) / 1000.0f;
      const float p = pow_unit(x, s);
      worst = std::max(worst, std::abs(double(p) - std::pow(double(x), double(s))));
      EXPECT_TRUE(p == 0.0f || std::fpclassify(p) == FP_NORMAL) << "shininess " << s << " x " << x;
    }
    EXPECT_LT(worst, 2e-6) << "shininess " << s;
    EXPECT_EQ(pow_unit(1.0f, s), 1.0f) << s;
    EXPECT_EQ(pow_unit(1.0000001f, s), 1.0f) << s;  // a dot of unit vectors may exceed 1
    EXPECT_EQ(pow_unit(0.0f, s), 0.0f) << s;
    EXPECT_EQ(pow_unit(-0.2f, s), 0.0f) << s;
  }
  EXPECT_EQ(pow_unit(0.3f, 0.0f), 1.0f);
  EXPECT_EQ(pow_unit(0.5f, 1.0f), 0.5f);
  EXPECT_EQ(pow_unit(0.5f, 20.0f), std::ldexp(1.0f, -20));
}

TEST(Pcg32, IsDeterministicAndUniform) {
  Pcg32 a(42), b(42), c(43);
  EXPECT_EQ(a.next_uint(), b.next_uint());
  EXPECT_NE(a.next_uint(), c.next_uint());
  Pcg32 rng(7);
  double sum = 0.0, sum_sq = 0.0;
  constexpr int kN = 200000;
  for (int i = 0; i < kN; ++i) {
    const float u = rng.next_float();
    ASSERT_GE(u, 0.0f);
    ASSERT_LT(u, 1.0f);
    sum += u;
    sum_sq += double(u) * u;
  }
  // Mean 1/2 and variance 1/12, within 5 standard errors.
  EXPECT_NEAR(sum / kN, 0.5, 5.0 * std::sqrt(1.0 / 12.0 / kN));
  EXPECT_NEAR(sum_sq / kN - (sum / kN) * (sum / kN), 1.0 / 12.0, 2e-3);
}

TEST(MemoryBudget, RejectsHugeAllocationsAndOverflow) {
  EXPECT_THROW(check_memory_budget("test", memory_budget_bytes() + 1), OutOfMemoryBudget);
  try {
    check_memory_budget("voxel data from big.nii.gz", memory_budget_bytes() + 1);
  } catch (const OutOfMemoryBudget& e) {
    // What was refused, and how to change the budget.
    EXPECT_NE(std::string(e.what()).find("voxel data from big.nii.gz needs"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("PENUMBRA_MEMORY_BUDGET_MB"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(check_memory_budget("test", 1024));
  EXPECT_EQ(checked_product({1ull << 40, 1ull << 40}), std::numeric_limits<std::uint64_t>::max());
  EXPECT_EQ(checked_product({3, 5, 7}), 105u);
}

TEST(Parallel, CoversEveryIndexExactlyOnce) {
  std::vector<std::atomic<int>> hits(10007);
  parallel_for(0, 10007, [&](std::int64_t a, std::int64_t b) {
    for (std::int64_t i = a; i < b; ++i) hits[std::size_t(i)]++;
  });
  for (const auto& h : hits) ASSERT_EQ(h.load(), 1);
  std::vector<std::atomic<int>> pixels(37 * 23);
  parallel_for_tiles(37, 23, 8, [&](int x0, int y0, int x1, int y1) {
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) pixels[std::size_t(y * 37 + x)]++;
  });
  for (const auto& p : pixels) ASSERT_EQ(p.load(), 1);
}

TEST(Parallel, ThreadCountCanBeLimited) {
  set_thread_count(1);
  EXPECT_EQ(thread_count(), 1);
  set_thread_count(0);
  EXPECT_GE(thread_count(), 1);
  EXPECT_THROW(set_thread_count(-1), InvalidArgument);
}

TEST(NumericCast, IntegersOnlyFromFiniteValuesInRange) {
  EXPECT_EQ(to_integer<int>(3.9), 3);
  EXPECT_EQ(to_integer<int>(-3.9), -3);
  EXPECT_EQ(to_integer<std::int16_t>(32767.5), 32767);
  EXPECT_EQ(to_integer<std::int16_t>(32768.0), std::nullopt);
  EXPECT_EQ(to_integer<std::int16_t>(-32768.0), -32768);
  EXPECT_EQ(to_integer<std::int16_t>(-32769.0), std::nullopt);
  EXPECT_EQ(to_integer<std::uint8_t>(-0.5), 0);
  EXPECT_EQ(to_integer<std::uint8_t>(-1.0), std::nullopt);
  EXPECT_EQ(to_integer<std::int64_t>(9.2e18), std::int64_t(9.2e18));
  EXPECT_EQ(to_integer<std::int64_t>(9.3e18), std::nullopt);
  EXPECT_EQ(to_integer<std::uint64_t>(1.8e19), std::uint64_t(1.8e19));
  EXPECT_EQ(to_integer<std::uint64_t>(1.9e19), std::nullopt);
  for (const double bad : {1e30, -1e30, std::nan(""), HUGE_VAL, -HUGE_VAL}) {
    EXPECT_EQ(to_integer<int>(bad), std::nullopt) << bad;
    EXPECT_EQ(to_integer<std::uint64_t>(bad), std::nullopt) << bad;
  }
  EXPECT_EQ(to_exact_integer<int>(12.0), 12);
  EXPECT_EQ(to_exact_integer<int>(12.5), std::nullopt);
  EXPECT_EQ(to_exact_integer<int>(std::nan("")), std::nullopt);
}

TEST(NumericCast, FloatsOnlyFromValuesInTheFloatRange) {
  EXPECT_EQ(to_float(0.5), 0.5f);
  EXPECT_EQ(to_float(-3.0e38), -3.0e38f);
  EXPECT_EQ(to_float(1e300), std::nullopt);
  EXPECT_EQ(to_float(-1e39), std::nullopt);
  EXPECT_TRUE(std::isinf(*to_float(HUGE_VAL)));
  EXPECT_TRUE(std::isnan(*to_float(std::nan(""))));
}

}  // namespace
}  // namespace penumbra

#include "penumbra/base/error.h"
#include "penumbra/scene/transfer_function.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <type_traits>

namespace penumbra {
namespace {

// A std::vector of tables (one per light or mesh) moves them when it grows
// instead of copying them.
static_assert(std::is_nothrow_move_constructible_v<TransferFunctionTable>);
static_assert(std::is_nothrow_move_assignable_v<TransferFunctionTable>);

TransferFunction three_point_tf() {
  return TransferFunction({{0.0f, vec3(0.0f), 0.0f}, {0.5f, vec3(1.0f, 0.5f, 0.0f), 0.8f}, {1.0f, vec3(1.0f), 0.2f}});
}

TEST(TransferFunction, EvaluatesPiecewiseLinearlyAndClampsOutside) {
  const TransferFunction tf = three_point_tf();
  EXPECT_NEAR(tf.evaluate(0.25f).a, 0.4f, 1e-6f);
  EXPECT_NEAR(tf.evaluate(0.75f).a, 0.5f, 1e-6f);
  EXPECT_NEAR(tf.evaluate(0.25f).g, 0.25f, 1e-6f);
  EXPECT_FLOAT_EQ(tf.evaluate(-1.0f).a, 0.0f);
  EXPECT_FLOAT_EQ(tf.evaluate(2.0f).a, 0.2f);
}

TEST(TransferFunction, MaxOpacityIsExactOverIntervals) {
  const TransferFunction tf = three_point_tf();
  EXPECT_FLOAT_EQ(tf.max_opacity(0.0f, 1.0f), 0.8f);
  EXPECT_NEAR(tf.max_opacity(0.0f, 0.25f), 0.4f, 1e-6f);
  EXPECT_NEAR(tf.max_opacity(0.6f, 0.9f), 0.68f, 1e-6f);  // 0.8 + 0.2 * (0.2 - 0.8)
  EXPECT_NEAR(tf.max_opacity(0.75f, 1.0f), 0.5f, 1e-6f);
}

TEST(TransferFunction, RejectsInvalidPoints) {
  EXPECT_THROW(TransferFunction(std::vector<TransferFunctionPoint>{}), InvalidArgument);
  EXPECT_THROW(TransferFunction({{0.0f, vec3(1.0f), 1.5f}}), InvalidArgument);
  EXPECT_THROW(TransferFunction({{std::nanf(""), vec3(1.0f), 0.5f}}), InvalidArgument);
  TransferFunction tf;
  EXPECT_THROW(tf.set_range(vec2(1.0f, 1.0f)), InvalidArgument);
  EXPECT_THROW(tf.set_unit_length(0.0f), InvalidArgument);
  EXPECT_THROW(tf.set_density_scale(-1.0f), InvalidArgument);
}

TEST(TransferFunctionTable, ExtinctionFollowsTheOpticalModel) {
  // alpha is the opacity of a slab of unit_length: exp(-sigma * unit_length) = 1 - alpha.
  TransferFunction tf({{0.0f, vec3(1.0f), 0.3f}, {1.0f, vec3(1.0f), 0.3f}});
  tf.set_density_scale(2.0f);
  const TransferFunctionTable table(tf, vec2(0.0f, 10.0f), 0.5f);
  const float sigma = table.view().lookup(4.0f).a;
  EXPECT_NEAR(std::exp(-sigma * 0.5f / 2.0f), 0.7f, 1e-5f);
}

TEST(TransferFunctionTable, LookupMapsDataValuesThroughTheRange) {
  const TransferFunction tf = three_point_tf();
  const TransferFunctionTable table(tf, vec2(100.0f, 300.0f), 1.0f);
  const TransferFunctionView v = table.view();
  EXPECT_NEAR(v.lookup(200.0f).r, 1.0f, 1e-3f);
  EXPECT_NEAR(v.lookup(150.0f).g, 0.25f, 1e-3f);
  EXPECT_NEAR(v.lookup(200.0f).a, -std::log(0.2f), 1e-3f);
  EXPECT_FLOAT_EQ(v.lookup(-1e9f).a, 0.0f);
  EXPECT_EQ(v.lookup(std::numeric_limits<float>::quiet_NaN()), vec4(0.0f));
  EXPECT_EQ(v.lookup(std::numeric_limits<float>::infinity()), vec4(0.0f));
}

TEST(TransferFunctionTable, MaxExtinctionBoundsEveryLookupInTheRange) {
  const TransferFunction tf = three_point_tf();
  const TransferFunctionTable table(tf, vec2(0.0f, 1.0f), 1.0f);
  const TransferFunctionView v = table.view();
  std::uint32_t s = 1;
  for (int trial = 0; trial < 2000; ++trial) {
    s = s * 1664525u + 1013904223u;
    const float a = float(s >> 8) / float(1 << 24);
    s = s * 1664525u + 1013904223u;
    const float b = float(s >> 8) / float(1 << 24);
    const float lo = std::min(a, b), hi = std::max(a, b);
    const float bound = table.max_extinction(lo, hi);
    for (int k = 0; k <= 16; ++k) {
      ASSERT_LE(v.lookup(lo + (hi - lo) * float(k) / 16.0f).a, bound + 1e-6f);
    }
    // The bound is tight up to one table entry.
    EXPECT_LE(bound, -std::log(1.0f - tf.max_opacity(lo - 1.0f / 4095.0f, hi + 1.0f / 4095.0f)) + 1e-4f);
  }
  EXPECT_FLOAT_EQ(table.max_extinction(std::numeric_limits<float>::infinity(), -1.0f), 0.0f);
}

}  // namespace
}  // namespace penumbra

#include "penumbra/techniques/convolution/preintegration.h"

#include "penumbra/base/error.h"
#include "penumbra/base/rng.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <deque>
#include <vector>

namespace penumbra {
namespace {

// A TF view over [0, 1] from hand-made (rgb, sigma_t) entries (its sigma
// column lives as long as the test binary).
TransferFunctionView view_of(const std::vector<vec4>& entries) {
  static std::deque<std::vector<float>> columns;
  std::vector<float>& sigma = columns.emplace_back();
  for (const vec4& e : entries) sigma.push_back(e.a);
  TransferFunctionView v;
  v.entries = entries.data();
  v.sigma = sigma.data();
  v.size = int(entries.size());
  v.value_min = 0.0f;
  v.index_scale = float(v.size - 1);
  return v;
}

// Brute-force reference: the segment's integrals by the midpoint rule over
// many steps in double, straight from the definitions in preintegration.h.
vec4 reference_segment(const TransferFunctionView& tf, float s_front, float s_back, float length) {
  const int steps = 20000;
  const double dx = double(length) / steps;
  double tau = 0.0;
  glm::dvec3 colour(0.0);
  for (int k = 0; k < steps; ++k) {
    const double t = (k + 0.5) / steps;
    const vec4 e = tf.lookup(float(s_front + t * (s_back - s_front)));
    const double sigma = e.a;
    // Transmittance to the middle of the step, then this step's scattering.
    colour += glm::dvec3(vec3(e)) * sigma * std::exp(-(tau + 0.5 * sigma * dx)) * dx;
    tau += sigma * dx;
  }
  const double alpha = -std::expm1(-tau);
  return vec4(vec3(alpha > 0.0 ? colour / alpha : glm::dvec3(0.0)), float(alpha));
}

// Front-to-back composite of two segments, (colour, alpha) each.
vec4 over(vec4 front, vec4 back) {
  const float alpha = front.a + (1.0f - front.a) * back.a;
  const vec3 c = front.a * vec3(front) + (1.0f - front.a) * back.a * vec3(back);
  return vec4(alpha > 0.0f ? c / alpha : vec3(0.0f), alpha);
}

void expect_near4(vec4 a, vec4 b, float tol) {
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(a[k], b[k], tol) << "component " << k;
}

TEST(ConvolutionPreintegration, ConstantTfIsExact) {
  const vec3 colour(0.2f, 0.5f, 0.8f);
  const std::vector<vec4> entries(5, vec4(colour, 3.0f));
  const float length = 0.7f;
  const PreintegrationTable table(view_of(entries), length, 16);
  const PreintegrationView v = table.view();
  const float alpha = float(-std::expm1(-3.0 * 0.7));
  // Float rounding only: every sub-segment's mean colour is the TF colour and
  // every entry's alpha comes from the same closed form.
  for (float sf : {0.0f, 0.13f, 0.5f, 1.0f})
    for (float sb : {0.0f, 0.37f, 0.5f, 0.99f}) expect_near4(v.lookup(sf, sb), vec4(colour, alpha), 1e-6f);
}

TEST(ConvolutionPreintegration, EqualEndsGiveTheSingleSample) {
  TransferFunction tf({{0.0f, vec3(1.0f, 0.0f, 0.0f), 0.0f},
                       {0.3f, vec3(0.0f, 1.0f, 0.0f), 0.6f},
                       {0.7f, vec3(0.0f, 0.0f, 1.0f), 0.2f},
                       {1.0f, vec3(1.0f, 1.0f, 1.0f), 0.9f}});
  const TransferFunctionTable tf_table(tf, vec2(10.0f, 30.0f), 0.5f, 1024);
  const TransferFunctionView tfv = tf_table.view();
  const float length = 0.8f;
  const int n = 64;
  const PreintegrationTable table(tfv, length, n);
  const PreintegrationView v = table.view();
  for (int i = 0; i < n; i += 7) {
    const float s = 10.0f + 20.0f * float(i) / float(n - 1);
    const vec4 sample = tfv.lookup(s);
    // At table values the diagonal entry is read back (float rounding of s).
    expect_near4(v.lookup(s, s), vec4(vec3(sample), float(-std::expm1(-double(length) * sample.a))), 2e-5f);
  }
}

TEST(ConvolutionPreintegration, LinearSigmaRampMatchesTheAnalyticIntegral) {
  // sigma(s) = 0.5 + 4 s over [0, 1]: the segment's mean is sigma((s_f + s_b) / 2).
  const std::vector<vec4> entries = {vec4(1.0f, 0.5f, 0.25f, 0.5f), vec4(1.0f, 0.5f, 0.25f, 4.5f)};
  const float length = 1.0f;
  const int n = 64;
  const PreintegrationTable table(view_of(entries), length, n);
  const PreintegrationView v = table.view();
  const auto analytic = [&](float sf, float sb) {
    return float(-std::expm1(-double(length) * (0.5 + 4.0 * 0.5 * (double(sf) + double(sb)))));
  };
  for (int i = 0; i < n; i += 5)
    for (int j = 0; j < n; j += 3) {
      const float sf = float(i) / float(n - 1), sb = float(j) / float(n - 1);
      EXPECT_NEAR(v.lookup(sf, sb).a, analytic(sf, sb), 1e-6f);  // exact at table values
    }
  // Between table values: bilinear error <= h^2 / 8 * (|a_xx| + |a_yy|) with
  // |a_xx| <= (4 L / 2)^2 = 4 and h = 1/63: 2.5e-4.
  Pcg32 rng(9);
  for (int k = 0; k < 200; ++k) {
    const float sf = rng.next_float(), sb = rng.next_float();
    EXPECT_NEAR(v.lookup(sf, sb).a, analytic(sf, sb), 2.5e-4f);
  }
}

TEST(ConvolutionPreintegration, ColourIsAttenuatedFromTheFront) {
  // Colour red -> blue over the range, sigma 3 everywhere, L = 1: the front
  // dominates the mean colour (the unattenuated mean would be halfway).
  const std::vector<vec4> entries = {vec4(1.0f, 0.0f, 0.0f, 3.0f), vec4(0.0f, 0.0f, 1.0f, 3.0f)};
  const TransferFunctionView tfv = view_of(entries);
  const int n = 128;
  const PreintegrationTable table(tfv, 1.0f, n);
  const PreintegrationView v = table.view();
  for (auto [sf, sb] : {std::pair{0.0f, 1.0f}, std::pair{1.0f, 0.0f}, std::pair{0.25f, 0.75f}}) {
    const vec4 got = v.lookup(sf, sb), want = reference_segment(tfv, sf, sb, 1.0f);
    // Each sub-segment takes its sigma-weighted mean colour instead of the
    // attenuation-weighted one: off by about the colour change over one table
    // step (1/127) times the sub-segment's optical depth (3/127) / 12 ~ 2e-5
    // per step (measured 3e-5 in all); 2e-4 leaves rounding room. Ignoring the
    // attenuation inside the segment would be off by ~0.2.
    expect_near4(got, want, 2e-4f);
    // And it is not the unattenuated midpoint colour.
    EXPECT_GT(std::abs(got.r - 0.5f * (1.0f - sf + 1.0f - sb)), 0.1f);
  }
}

TEST(ConvolutionPreintegration, TwoHalvesCompositeToTheWhole) {
  TransferFunction tf({{0.0f, vec3(0.9f, 0.1f, 0.1f), 0.05f},
                       {0.4f, vec3(0.1f, 0.9f, 0.2f), 0.7f},
                       {0.6f, vec3(0.2f, 0.3f, 0.9f), 0.1f},
                       {1.0f, vec3(0.8f, 0.8f, 0.1f), 0.95f}});
  const TransferFunctionTable tf_table(tf, vec2(0.0f, 1.0f), 0.25f, 1024);
  const int n = 129;
  const float length = 0.6f;
  const PreintegrationTable whole(tf_table.view(), length, n);
  const PreintegrationTable half(tf_table.view(), 0.5f * length, n);
  // Table values two steps apart: both halves' sub-segments have the same
  // length and extinction as the whole's, so only rounding differs.
  for (int i = 0; i < n; i += 11)
    for (int j = i % 2; j < n; j += 6) {
      const int m = (i + j) / 2;
      const float sf = float(i) / float(n - 1), sm = float(m) / float(n - 1), sb = float(j) / float(n - 1);
      if ((i + j) % 2 != 0) continue;
      expect_near4(over(half.view().lookup(sf, sm), half.view().lookup(sm, sb)), whole.view().lookup(sf, sb),
                   2e-5f);
    }
  // Anywhere: within the bilinear interpolation error of the three lookups
  // (h = 1/128; colours change by up to ~4 per value unit near the TF's
  // knots, so a step moves them by ~0.03 and bilinear interpolation of a
  // kinked function errs by up to a quarter of that; measured 2e-3).
  Pcg32 rng(4);
  for (int k = 0; k < 300; ++k) {
    const float sf = rng.next_float(), sb = rng.next_float(), sm = 0.5f * (sf + sb);
    expect_near4(over(half.view().lookup(sf, sm), half.view().lookup(sm, sb)), whole.view().lookup(sf, sb),
                 8e-3f);
  }
}

TEST(ConvolutionPreintegration, MatchesBruteForceAnywhere) {
  TransferFunction tf({{0.0f, vec3(0.9f, 0.1f, 0.1f), 0.05f},
                       {0.4f, vec3(0.1f, 0.9f, 0.2f), 0.7f},
                       {0.6f, vec3(0.2f, 0.3f, 0.9f), 0.1f},
                       {1.0f, vec3(0.8f, 0.8f, 0.1f), 0.95f}});
  const TransferFunctionTable tf_table(tf, vec2(-2.0f, 6.0f), 0.25f, 1024);
  const float length = 0.6f;
  const PreintegrationTable table(tf_table.view(), length, 129);
  Pcg32 rng(21);
  for (int k = 0; k < 100; ++k) {
    const float sf = -2.0f + 8.0f * rng.next_float(), sb = -2.0f + 8.0f * rng.next_float();
    // Bilinear interpolation between table values (same bound as above;
    // measured 2.8e-3) against the definition integrated by brute force.
    expect_near4(table.view().lookup(sf, sb), reference_segment(tf_table.view(), sf, sb, length), 8e-3f);
  }
}

TEST(ConvolutionPreintegration, CatchesASpikeThatEndPointSamplesMiss) {
  // Transparent red except a green spike of height 200 around s = 0.5, width
  // 0.002 at its base: int sigma ds = 0.2.
  std::vector<vec4> entries(1001, vec4(1.0f, 0.0f, 0.0f, 0.0f));
  for (int e = 499; e <= 501; ++e) entries[std::size_t(e)] = vec4(0.0f, 1.0f, 0.0f, 0.0f);
  entries[500].a = 200.0f;
  const TransferFunctionView tfv = view_of(entries);
  const float sf = 51.0f / 255.0f, sb = 204.0f / 255.0f, length = 1.0f;  // table values at N = 256
  // Point samples at the ends see nothing.
  EXPECT_EQ(tfv.lookup(sf).a, 0.0f);
  EXPECT_EQ(tfv.lookup(sb).a, 0.0f);
  const PreintegrationTable table(tfv, length, 256);
  const vec4 got = table.view().lookup(sf, sb);
  const float alpha = float(-std::expm1(-double(length) * 0.2 / (double(sb) - double(sf))));
  EXPECT_GT(got.a, 0.25f);
  EXPECT_NEAR(got.a, alpha, 1e-4f);  // S is exact; float rounding of the ends
  expect_near4(got, vec4(0.0f, 1.0f, 0.0f, alpha), 1e-4f);
  // Both directions see the same opacity.
  EXPECT_NEAR(table.view().lookup(sb, sf).a, alpha, 1e-4f);
}

TEST(ConvolutionPreintegration, LookupHandlesOddValues) {
  const std::vector<vec4> entries = {vec4(1.0f, 0.0f, 0.0f, 1.0f), vec4(0.0f, 1.0f, 0.0f, 2.0f)};
  const PreintegrationTable table(view_of(entries), 1.0f, 8);
  const PreintegrationView v = table.view();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(v.lookup(nan, 0.5f), vec4(0.0f));
  EXPECT_EQ(v.lookup(0.5f, std::numeric_limits<float>::infinity()), vec4(0.0f));
  expect_near4(v.lookup(-5.0f, 7.0f), v.lookup(0.0f, 1.0f), 1e-7f);  // clamped to the range
}

TEST(ConvolutionPreintegration, RejectsBadArguments) {
  const std::vector<vec4> entries = {vec4(1.0f), vec4(1.0f)};
  const TransferFunctionView tfv = view_of(entries);
  EXPECT_THROW(PreintegrationTable(tfv, 1.0f, 1), InvalidArgument);
  EXPECT_THROW(PreintegrationTable(tfv, 1.0f, 0), InvalidArgument);
  EXPECT_THROW(PreintegrationTable(tfv, 1.0f, PreintegrationTable::kMaxSize + 1), InvalidArgument);
  EXPECT_THROW(PreintegrationTable(tfv, 0.0f, 16), InvalidArgument);
  EXPECT_THROW(PreintegrationTable(tfv, std::numeric_limits<float>::quiet_NaN(), 16), InvalidArgument);
  EXPECT_THROW(PreintegrationTable(TransferFunctionView{}, 1.0f, 16), InvalidArgument);
  try {
    PreintegrationTable(tfv, 1.0f, 1);
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.name(), "size");
  }
}

TEST(ConvolutionPreintegration, CacheRebuildsOnlyOnChange) {
  std::vector<vec4> entries = {vec4(1.0f, 0.0f, 0.0f, 1.0f), vec4(0.0f, 1.0f, 0.0f, 2.0f)};
  PreintegrationCache cache;
  EXPECT_TRUE(cache.update(view_of(entries), 1.0f, 16));
  EXPECT_FALSE(cache.update(view_of(entries), 1.0f, 16));
  EXPECT_TRUE(cache.update(view_of(entries), 2.0f, 16));
  EXPECT_FALSE(cache.update(view_of(entries), 2.0f, 16));
  const float before = cache.view().lookup(1.0f, 1.0f).a;
  entries[1].a = 5.0f;  // edited in place: same pointer, new content
  EXPECT_TRUE(cache.update(view_of(entries), 2.0f, 16));
  EXPECT_GT(cache.view().lookup(1.0f, 1.0f).a, before);
  EXPECT_TRUE(cache.update(view_of(entries), 2.0f, 32));
  EXPECT_EQ(cache.table().size(), 32);
}

}  // namespace
}  // namespace penumbra

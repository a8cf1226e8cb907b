#include "penumbra/analysis/color_space.h"

#include <gtest/gtest.h>

namespace penumbra {
namespace {

void expect_lab_near(const Lab& lab, double l, double a, double b, double tolerance) {
  EXPECT_NEAR(lab.l, l, tolerance);
  EXPECT_NEAR(lab.a, a, tolerance);
  EXPECT_NEAR(lab.b, b, tolerance);
}

TEST(ColorSpace, WhiteAndBlackAreTheEndsOfTheLightnessAxis) {
  const Lab white = srgb_linear_to_lab(vec3(1.0f));
  EXPECT_EQ(white.l, 100.0);
  EXPECT_EQ(white.a, 0.0);
  EXPECT_EQ(white.b, 0.0);
  expect_lab_near(srgb_linear_to_lab(vec3(0.0f)), 0.0, 0.0, 0.0, 1e-12);
}

TEST(ColorSpace, GreysAreNeutral) {
  for (float grey : {0.001f, 0.05f, 0.18f, 0.5f, 0.9f}) {
    const Lab lab = srgb_linear_to_lab(vec3(grey));
    EXPECT_NEAR(lab.a, 0.0, 1e-9) << grey;
    EXPECT_NEAR(lab.b, 0.0, 1e-9) << grey;
  }
}

TEST(ColorSpace, LightnessFollowsCie) {
  // 18% grey: L* = 116 * 0.18^(1/3) - 16.
  EXPECT_NEAR(srgb_linear_to_lab(vec3(0.18f)).l, 49.4961, 1e-3);
  // Below (6/29)^3 the curve is the straight line L* = (29/3)^3 Y.
  EXPECT_NEAR(srgb_linear_to_lab(vec3(0.001f)).l, 0.903296, 1e-5);
}

TEST(ColorSpace, PrimariesMatchPublishedLab) {
  // Published sRGB primaries in L*a*b* (D65), e.g. B. Lindbloom's calculator.
  expect_lab_near(srgb_linear_to_lab(vec3(1.0f, 0.0f, 0.0f)), 53.24, 80.09, 67.20, 0.05);
  expect_lab_near(srgb_linear_to_lab(vec3(0.0f, 1.0f, 0.0f)), 87.73, -86.18, 83.18, 0.05);
  expect_lab_near(srgb_linear_to_lab(vec3(0.0f, 0.0f, 1.0f)), 32.30, 79.19, -107.86, 0.05);
}

TEST(ColorSpace, SrgbTransferFunctionRoundTrips) {
  EXPECT_NEAR(srgb_encode(0.5f), 0.735357f, 1e-5f);
  EXPECT_NEAR(srgb_encode(0.002f), 0.02584f, 1e-6f);  // linear toe: 12.92 x
  EXPECT_FLOAT_EQ(srgb_encode(2.0f), 1.0f);
  EXPECT_FLOAT_EQ(srgb_encode(-1.0f), 0.0f);
  for (float v = 0.0f; v <= 1.0f; v += 0.03125f) EXPECT_NEAR(srgb_decode(srgb_encode(v)), v, 1e-6f) << v;
}

}  // namespace
}  // namespace penumbra

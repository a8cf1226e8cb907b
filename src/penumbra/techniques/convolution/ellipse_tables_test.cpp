#include "penumbra/techniques/convolution/ellipse_tables.h"

#include <gtest/gtest.h>

#include <cmath>

namespace penumbra {
namespace {

// Arc-length density variances of the ellipse (a, b) by brute quadrature,
// independent of the elliptic-integral expression.
glm::dvec2 brute_variances(double a, double b) {
  const int n = 200000;
  double len = 0.0, xx = 0.0, yy = 0.0;
  for (int i = 0; i < n; ++i) {
    const double th = 6.283185307179586 * (i + 0.5) / n;
    const double ds = std::hypot(a * std::sin(th), b * std::cos(th));
    len += ds;
    xx += ds * a * a * std::cos(th) * std::cos(th);
    yy += ds * b * b * std::sin(th) * std::sin(th);
  }
  return glm::dvec2(xx / len, yy / len);
}

TEST(ConvolutionEllipse, EllipticIntegralsMatchKnownValues) {
  EXPECT_NEAR(elliptic_k(0.0), 1.5707963267948966, 1e-12);
  EXPECT_NEAR(elliptic_e(0.0), 1.5707963267948966, 1e-12);
  // K(1/sqrt 2) = 1.854074677301372, E(1/sqrt 2) = 1.350643881047675 (A&S table 17.1).
  EXPECT_NEAR(elliptic_k(std::sqrt(0.5)), 1.854074677301372, 1e-12);
  EXPECT_NEAR(elliptic_e(std::sqrt(0.5)), 1.350643881047675, 1e-12);
}

TEST(ConvolutionEllipse, AppendixExpressionMatchesQuadrature) {
  EXPECT_NEAR(ellipse_var_x(0.0), 1.0 / 3.0, 1e-12);
  EXPECT_NEAR(ellipse_var_x(1.0), 0.5, 1e-12);
  for (double b : {0.01, 0.1, 0.3, 0.5, 0.8, 0.99}) {
    EXPECT_NEAR(ellipse_var_x(b), brute_variances(1.0, b).x, 1e-6) << b;
  }
}

// Appendix A.7 / section 3.4: the radii from the two tables reproduce the
// requested variances within 1% (checked by quadrature of the ellipse).
TEST(ConvolutionEllipse, TablesReproduceRequestedVariancesWithinOnePercent) {
  const EllipseTables& tables = EllipseTables::instance();
  double worst = 0.0;
  for (double vx : {1e-3, 0.2, 1.0, 3.2, 40.0}) {
    for (double ratio : {0.0, 1e-4, 0.01, 0.1, 0.5, 1.0, 2.0, 10.0, 1e3}) {
      const double vy = vx * ratio;
      const glm::dvec2 r = tables.radii(vx, vy);
      const glm::dvec2 v = brute_variances(r.x, r.y);
      EXPECT_NEAR(v.x, vx, 0.01 * std::max(vx, vy)) << vx << " " << vy;
      EXPECT_NEAR(v.y, vy, 0.01 * std::max(vx, vy)) << vx << " " << vy;
      if (ratio > 0.0) {
        EXPECT_NEAR(v.x / vx, 1.0, 0.01) << vx << " " << vy;
        EXPECT_NEAR(v.y / vy, 1.0, 0.01) << vx << " " << vy;
        worst = std::max({worst, std::abs(v.x / vx - 1.0), std::abs(v.y / vy - 1.0)});
      }
    }
  }
  std::printf("ellipse tables: worst relative variance error %.2e\n", worst);
  EXPECT_EQ(tables.radii(0.0, 0.0), glm::dvec2(0.0));
}

}  // namespace
}  // namespace penumbra

#include "penumbra/render/microfacet.h"

#include <gtest/gtest.h>

#include <cmath>

namespace penumbra {
namespace {

// Midpoint quadrature over the hemisphere about +z of f(direction) dw.
template <class F>
double hemisphere_integral(F f, int n = 400) {
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double theta = (i + 0.5) * (kPi / 2.0) / n;
    for (int j = 0; j < 2 * n; ++j) {
      const double phi = (j + 0.5) * kPi / n;
      const vec3 w(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)),
                   float(std::cos(theta)));
      sum += f(w) * std::sin(theta) * (kPi / 2.0 / n) * (kPi / n);
    }
  }
  return sum;
}

// The GGX distribution is normalised: its projected area is the macro surface.
TEST(Microfacet, DistributionProjectsToUnitArea) {
  for (float alpha : {0.1f, 0.3f, 0.8f}) {
    const double area = hemisphere_integral([&](vec3 h) { return ggx_distribution(h.z, alpha) * h.z; });
    EXPECT_NEAR(area, 1.0, 0.01) << alpha;
  }
}

// With F0 = 1 the directional albedo int f_s cos dw is at most 1 (energy
// conservation) and, for a smooth surface, nearly 1 (separable Smith loses a
// few percent); F0 scales it at normal incidence (Schlick: F(0) = F0 there).
TEST(Microfacet, AlbedoConservesEnergy) {
  const vec3 n(0.0f, 0.0f, 1.0f);
  for (float alpha : {0.1f, 0.3f, 0.8f}) {
    for (float view_deg : {0.0f, 45.0f, 75.0f}) {
      const float t = glm::radians(view_deg);
      const vec3 v(std::sin(t), 0.0f, std::cos(t));
      const double albedo =
          hemisphere_integral([&](vec3 l) { return microfacet_specular(n, v, l, 1.0f, alpha) / kPi; }, 300);
      EXPECT_LE(albedo, 1.0) << alpha << " " << view_deg;
      if (alpha <= 0.1f && view_deg < 60.0f) {
        EXPECT_GT(albedo, 0.9) << view_deg;
      }
    }
  }
  const vec3 v(0.0f, 0.0f, 1.0f);
  const double full = hemisphere_integral([&](vec3 l) { return microfacet_specular(n, v, l, 1.0f, 0.05f); });
  const double part = hemisphere_integral([&](vec3 l) { return microfacet_specular(n, v, l, 0.04f, 0.05f); });
  EXPECT_NEAR(part / full, 0.04, 0.004);
}

// Reciprocal in viewer and light, zero below the surface, peaked at the mirror direction.
TEST(Microfacet, IsReciprocalAndPeaksAtTheMirror) {
  const vec3 n(0.0f, 0.0f, 1.0f);
  const vec3 a = glm::normalize(vec3(0.3f, 0.1f, 1.0f)), b = glm::normalize(vec3(-0.5f, 0.4f, 0.8f));
  EXPECT_NEAR(microfacet_specular(n, a, b, 0.04f, 0.3f) / b.z, microfacet_specular(n, b, a, 0.04f, 0.3f) / a.z, 1e-5f);
  EXPECT_EQ(microfacet_specular(n, a, vec3(0.0f, 0.0f, -1.0f), 0.04f, 0.3f), 0.0f);
  EXPECT_EQ(microfacet_specular(n, vec3(0.0f, 0.0f, -1.0f), a, 0.04f, 0.3f), 0.0f);
  const vec3 mirror(-a.x, -a.y, a.z);
  EXPECT_GT(microfacet_specular(n, a, mirror, 0.04f, 0.2f), microfacet_specular(n, a, b, 0.04f, 0.2f));
}

}  // namespace
}  // namespace penumbra

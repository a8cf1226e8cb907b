// The path kernel's pieces: phase-function sampling, and next-event
// estimation from an area light past an opaque edge, against analytic
// values.
#include "penumbra/render/scene_resources.h"
#include "penumbra/techniques/pathtrace/path_kernel.h"
#include "test_scene.h"

#include <gtest/gtest.h>

#include <cmath>

namespace penumbra {
namespace {

// HG moments: E[cos] = g and E[cos^2] = (1 + 2 g^2) / 3.
TEST(PathKernel, HenyeyGreensteinSamplesHaveTheRightMoments) {
  for (const float g : {-0.7f, 0.0f, 0.3f, 0.9f}) {
    SCOPED_TRACE(g);
    Pcg32 rng(29);
    const vec3 travel = glm::normalize(vec3(0.3f, -1.0f, 0.2f));
    const int n = 100000;
    double m1 = 0.0, m2 = 0.0;
    for (int i = 0; i < n; ++i) {
      const vec3 w = sample_hg(travel, g, vec2(rng.next_float(), rng.next_float()));
      ASSERT_NEAR(glm::length(w), 1.0f, 1e-5f);
      const double c = glm::dot(w, travel);
      m1 += c;
      m2 += c * c;
    }
    // |cos| <= 1, so each moment's standard error is below 1 / sqrt(n).
    EXPECT_NEAR(m1 / n, g, 4.0 / std::sqrt(double(n)));
    EXPECT_NEAR(m2 / n, (1.0 + 2.0 * g * g) / 3.0, 4.0 / std::sqrt(double(n)));
  }
}

double normal_cdf(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }

// An opaque half-plane slab (the `edge` volume: x < 0, world z in [5, 9] for
// 48^3, where the trilinear field crosses 0.5) over a floor at z = -20, lit
// straight down by a Gaussian distant light. Directions toward the light are
// (ox, oy, 1) normalised with ox, oy ~ N(0, s^2), s = tan(angle); the ray
// from floor point x clears the slab iff x + H ox > 0 with H the height of
// the slab's top (x > 0) or bottom (x < 0) above the floor, so the lit
// fraction is the Gaussian cdf Phi(x / (H s)) (Patel et al. 2013, Appendix:
// a Heaviside occluder under a Gaussian light). The estimate also carries the
// cosine at the floor, which the expected value integrates numerically.
TEST(PathKernel, GaussianLightPenumbraBehindAnEdgeIsTheGaussianCdf) {
  Scene scene = testing::procedural_scene("edge", ivec3(48));
  scene.set_transfer_function(testing::step_tf(0.5f, vec3(0.0f), 1.0f));
  Light light;
  light.type = LightType::Distant;
  light.profile = LightProfile::Gaussian;
  light.direction = vec3(0.0f, 0.0f, -1.0f);
  light.angle_deg = 10.0f;
  scene.set_lights({light});
  const float floor_z = -20.0f;
  scene.set_planes({Plane{vec3(0.0f, 0.0f, floor_z), vec3(0.0f, 0.0f, 1.0f), vec3(1.0f)}});
  SceneResources resources;
  resources.update(scene);
  const RenderView v = resources.view(scene);
  const double s = std::tan(glm::radians(double(light.angle_deg)));
  auto expected = [&](double x) {
    const double height = (x > 0.0 ? 9.0 : 5.0) - floor_z;
    // E[cos * lit] over the 2D Gaussian, by quadrature on a +-6 sd grid.
    double sum = 0.0, weights = 0.0;
    const int n = 241;
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        const double ox = (-6.0 + 12.0 * i / (n - 1)) * s;
        const double oy = (-6.0 + 12.0 * j / (n - 1)) * s;
        const double w = std::exp(-(ox * ox + oy * oy) / (2.0 * s * s));
        weights += w;
        if (x + height * ox > 0.0) sum += w / std::sqrt(1.0 + ox * ox + oy * oy);
      }
    }
    return sum / weights;
  };
  with_sampler(v.volume, [&](const auto& sampler) {
    const PathKernel<std::decay_t<decltype(sampler)>> kernel{&v, &v, sampler, PathSettings{}};
    const vec3 up(0.0f, 0.0f, 1.0f);
    for (const float x : {-12.0f, -5.0f, -2.0f, 0.0f, 2.0f, 5.0f, 12.0f}) {
      Pcg32 rng(std::uint64_t(x * 10.0f + 1000.0f));
      std::uint64_t lookups = 0;
      const int n = 6000;
      double sum = 0.0;
      for (int i = 0; i < n; ++i) {
        const vec3 e = kernel.direct_light(vec3(x, 0.0f, floor_z), 0, [&](vec3 l) { return glm::dot(up, l); }, rng,
                                           lookups);
        sum += e.x;
      }
      // Binary visibility: sd <= 0.5, standard error <= 0.0065; 4 of them,
      // plus 0.02 for the one-voxel-wide trilinear edge of the occluder
      // (d Phi / dx at the edge is 1 / (sqrt(2 pi) H s) ~ 0.08 per voxel,
      // and half a voxel of blur shifts it by ~0.02).
      EXPECT_NEAR(sum / n, expected(x), 4.0 * 0.5 / std::sqrt(double(n)) + 0.02) << "floor x = " << x;
    }
    return 0;
  });
  EXPECT_NEAR(expected(-12.0), normal_cdf(-12.0 / (25.0 * s)), 0.02);  // the quadrature is the cdf, nearly
}

}  // namespace
}  // namespace penumbra

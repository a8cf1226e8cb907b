// The mapping of a scene light to Patel et al.'s Gaussian light on the slab
// plane (gaussian_light.h): for a light straight along the view axis whose
// frame is the camera's (right, up), the covariance is exactly the rotated
// diag(tan^2 ax, tan^2 ay); for a tilted light it is the light-frame
// covariance carried by the Jacobian of d -> mu (checked by finite
// differences), and it matches the spread of the directions the path tracer
// samples (the two conventions for the frame and its rotation agree).
#include "penumbra/techniques/convolution/gaussian_light.h"

#include "penumbra/base/rng.h"
#include "penumbra/scene/light_sampling.h"

#include <gtest/gtest.h>

#include <cmath>

namespace penumbra {
namespace {

Light anisotropic_light(vec3 direction, float ax, float ay, float rotation) {
  Light l;
  l.type = LightType::Distant;
  l.profile = LightProfile::Gaussian;
  l.direction = glm::normalize(direction);
  l.angle_deg = ax;
  l.angle_y_deg = ay;
  l.rotation_deg = rotation;
  return l;
}

// A camera looking along `forward` whose right and up are the unrotated light
// frame of a light travelling along `forward` (frame of c = -forward).
CameraView camera_along(vec3 forward) {
  CameraView cam;
  cam.forward = glm::normalize(forward);
  distant_light_frame(-cam.forward, 0.0f, cam.right, cam.up);
  return cam;
}

// mu(d) = (d . r, d . u) / (d . f) in double precision.
glm::dvec2 slope(dvec3 d, const CameraView& cam) {
  const double f = glm::dot(d, dvec3(cam.forward));
  return glm::dvec2(glm::dot(d, dvec3(cam.right)), glm::dot(d, dvec3(cam.up))) / f;
}

TEST(GaussianLight, AlongTheViewAxisTheCovarianceIsTheRotatedDiagonal) {
  // The default camera (forward -z, right +x, up +y) and an arbitrary one
  // whose (right, up) is the light frame; c = -forward either way.
  for (const vec3& forward : {vec3(0.0f, 0.0f, -1.0f), vec3(0.3f, -0.5f, -0.8f)}) {
    const CameraView cam = camera_along(forward);
    for (const float rotation : {0.0f, 30.0f, -70.0f, 125.0f}) {
      const Light l = anisotropic_light(cam.forward, 4.0f, 15.0f, rotation);
      const GaussianLight g = gaussian_light(l, cam, vec3(0.0f), LightOverride{});
      const double vx = std::pow(std::tan(glm::radians(4.0)), 2.0), vy = std::pow(std::tan(glm::radians(15.0)), 2.0);
      const double c = std::cos(glm::radians(double(rotation))), s = std::sin(glm::radians(double(rotation)));
      // R diag(vx, vy) R^T written out, R = [[c, -s], [s, c]].
      const double exx = c * c * vx + s * s * vy, eyy = s * s * vx + c * c * vy, exy = c * s * (vx - vy);
      // Float round-off of a few operations on values <= 0.07: 1e-6 absolute.
      EXPECT_NEAR(g.covariance[0][0], exx, 1e-6);
      EXPECT_NEAR(g.covariance[1][1], eyy, 1e-6);
      EXPECT_NEAR(g.covariance[1][0], exy, 1e-6);
      EXPECT_NEAR(g.covariance[0][1], exy, 1e-6);
      EXPECT_NEAR(glm::length(g.mu), 0.0f, 1e-6f);
      // And rotated_covariance (the technique's own override) agrees.
      const glm::mat2 r = rotated_covariance(float(vx), float(vy), rotation);
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) EXPECT_NEAR(g.covariance[i][j], r[i][j], 1e-6f);
    }
  }
}

// For a tilted light, J's columns are the derivatives of mu along the light
// frame's axes; central differences in double with step h have error
// O(h^2 mu''') ~ 1e-8, far below the float tolerance (1e-5 of the entries).
TEST(GaussianLight, TiltedLightCovarianceIsTheJacobianImageByFiniteDifferences) {
  const CameraView cam = camera_along(vec3(0.0f, 0.0f, -1.0f));
  for (const float rotation : {0.0f, -70.0f, 40.0f}) {
    const Light l = anisotropic_light(vec3(0.5f, -0.3f, -1.0f), 2.0f, 10.0f, rotation);
    const GaussianLight g = gaussian_light(l, cam, vec3(0.0f), LightOverride{});
    vec3 a, b;
    distant_light_frame(-l.direction, rotation, a, b);
    const dvec3 c = -dvec3(l.direction);
    const double h = 1e-4;
    // The light travels along -(c + x a + y b).
    auto column = [&](dvec3 axis) { return (slope(-(c + h * axis), cam) - slope(-(c - h * axis), cam)) / (2.0 * h); };
    const glm::dmat2 j(column(dvec3(a)), column(dvec3(b)));
    const double vx = std::pow(std::tan(glm::radians(2.0)), 2.0), vy = std::pow(std::tan(glm::radians(10.0)), 2.0);
    const glm::dmat2 expected = j * glm::dmat2(vx, 0.0, 0.0, vy) * glm::transpose(j);
    const double scale = std::max(expected[0][0], expected[1][1]);
    for (int i = 0; i < 2; ++i)
      for (int k = 0; k < 2; ++k) EXPECT_NEAR(g.covariance[i][k], expected[i][k], 1e-5 * scale) << i << k;
    // The tilt stretches the slope variance (mu = tan): not the untilted value.
    EXPECT_GT(std::abs(g.covariance[0][0] - rotated_covariance(float(vx), float(vy), rotation)[0][0]), 1e-2 * scale);
  }
}

// The path tracer's samples of the same light, mapped to slopes mu, have the
// covariance the convolution uses (to first order in the spread: with
// spreads of at most 3 degrees the second-order terms are ~tan^2(3 deg) ~ 0.3%
// of the entries). Statistical error: 5 standard errors of a second moment,
// sqrt((Sxx Syy + Sxy^2) / n), ~3.5% for n = 40000.
TEST(GaussianLight, CovarianceMatchesThePathTracersLightSamples) {
  const CameraView cam = camera_along(vec3(0.0f, 0.0f, -1.0f));
  const Light l = anisotropic_light(vec3(-0.4f, 0.6f, -1.0f), 1.0f, 3.0f, -70.0f);
  const GaussianLight g = gaussian_light(l, cam, vec3(0.0f), LightOverride{});
  Pcg32 rng(41);
  const int n = 40000;
  glm::dvec2 sum(0.0);
  glm::dmat2 second(0.0);
  for (int i = 0; i < n; ++i) {
    const vec3 w = sample_light_direction(l, vec3(0.0f), vec2(rng.next_float(), rng.next_float())).to_light;
    const glm::dvec2 m = slope(-dvec3(w), cam) - glm::dvec2(g.mu);
    sum += m;
    second += glm::outerProduct(m, m);
  }
  const glm::dmat2 cov = second / double(n) - glm::outerProduct(sum / double(n), sum / double(n));
  const double sxx = g.covariance[0][0], syy = g.covariance[1][1], sxy = g.covariance[1][0];
  auto tol = [&](double a, double b, double ab) { return 5.0 * std::sqrt((a * b + ab * ab) / n) + 0.01 * std::sqrt(a * b); };
  EXPECT_NEAR(cov[0][0], sxx, tol(sxx, sxx, sxx));
  EXPECT_NEAR(cov[1][1], syy, tol(syy, syy, syy));
  EXPECT_NEAR(cov[1][0], sxy, tol(sxx, syy, sxy));
  // The rotation's sign matters: the mirrored light has the opposite correlation.
  const double mirrored = gaussian_light(anisotropic_light(l.direction, 1.0f, 3.0f, 70.0f), cam, vec3(0.0f),
                                         LightOverride{}).covariance[1][0];
  EXPECT_GT(std::abs(cov[1][0] - mirrored), 10.0 * tol(sxx, syy, sxy));
}

// A sphere or disk light is the uniform cone it subtends from the box centre.
TEST(GaussianLight, SphereAndDiskLightsAreTheConeTheySubtendFromTheBoxCentre) {
  const CameraView cam = camera_along(vec3(0.2f, -0.3f, -1.0f));
  const vec3 centre(1.0f, 2.0f, 3.0f);
  const float distance = 50.0f, radius = 5.0f;
  Light cone;
  cone.type = LightType::Distant;
  cone.direction = cam.forward;
  cone.angle_deg = glm::degrees(std::atan(radius / std::sqrt(distance * distance - radius * radius)));
  const GaussianLight expected = gaussian_light(cone, cam, centre, LightOverride{});
  EXPECT_GT(expected.covariance[0][0], 1e-3f);
  for (LightType type : {LightType::Sphere, LightType::Disk}) {
    Light l;
    l.type = type;
    l.radius = radius;
    l.position = centre - distance * cam.forward;
    l.direction = cam.forward;
    const GaussianLight g = gaussian_light(l, cam, centre, LightOverride{});
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) EXPECT_NEAR(g.covariance[i][j], expected.covariance[i][j], 1e-6f);
    l.radius = 0.0f;  // a point light: hard
    EXPECT_EQ(gaussian_light(l, cam, centre, LightOverride{}).covariance, glm::mat2(0.0f));
  }
}

}  // namespace
}  // namespace penumbra

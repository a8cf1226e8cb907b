// Light sampling: each light's samples integrate its radiance to the value
// light.h defines (analytic integrals), the directions lie where the light
// is, and every area light becomes its point/directional limit.
#include "penumbra/base/rng.h"
#include "penumbra/scene/light_sampling.h"

#include <gtest/gtest.h>

#include <cmath>

namespace penumbra {
namespace {

vec2 next2(Pcg32& rng) { return vec2(rng.next_float(), rng.next_float()); }

Light make_light(LightType type) {
  Light l;
  l.type = type;
  l.intensity = 2.0f;
  l.color = vec3(1.0f, 0.5f, 0.25f);
  return l;
}

TEST(LightSampling, OrthonormalBasisIsOrthonormalAndRightHanded) {
  Pcg32 rng(3);
  for (int i = 0; i < 200; ++i) {
    const vec3 n = sample_uniform_sphere(next2(rng));
    vec3 t, b;
    orthonormal_basis(n, t, b);
    EXPECT_NEAR(glm::length(t), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::length(b), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(t, n), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(b, n), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(glm::cross(t, b), n), 1.0f, 1e-5f);
  }
}

TEST(LightSampling, DirectionalAndPointLightsAreTheirCentres) {
  Light d = make_light(LightType::Directional);
  d.direction = glm::normalize(vec3(1.0f, 0.0f, -1.0f));
  Light p = make_light(LightType::Point);
  p.position = vec3(3.0f, 4.0f, 0.0f);
  for (const Light& l : {d, p}) {
    const LightDirectionSample s = sample_light_direction(l, vec3(0.0f), vec2(0.3f, 0.7f));
    const LightSample c = sample_light(l, vec3(0.0f));
    EXPECT_NEAR(glm::distance(s.to_light, c.to_light), 0.0f, 1e-6f);
    EXPECT_EQ(s.distance, c.distance);
    EXPECT_NEAR(glm::distance(s.weight, c.radiance), 0.0f, 1e-6f);
  }
  // A point light 5 units away: I / d^2 (4 pi I / d^2 irradiance, in 4 pi units).
  EXPECT_NEAR(sample_light_direction(p, vec3(0.0f), vec2(0.5f)).weight.x, 2.0f / 25.0f, 1e-6f);
}

// Uniform radiance L_s = 4 I / r^2 over the subtended cone: the integral of
// radiance over directions is L_s 2 pi (1 - cos_max); the weight is that
// over 4 pi, for every sample.
TEST(LightSampling, SphereLightIntegratesItsRadianceAndHitsItsSurface) {
  Light l = make_light(LightType::Sphere);
  l.position = vec3(1.0f, 2.0f, 3.0f);
  l.radius = 2.0f;
  const vec3 p(4.0f, -1.0f, 5.0f);
  const float d = glm::distance(p, l.position);
  const float cos_max = std::sqrt(1.0f - l.radius * l.radius / (d * d));
  const float expected = 4.0f * l.intensity / (l.radius * l.radius) * 2.0f * kPi * (1.0f - cos_max) / (4.0f * kPi);
  Pcg32 rng(5);
  for (int i = 0; i < 500; ++i) {
    const LightDirectionSample s = sample_light_direction(l, p, next2(rng));
    ASSERT_NEAR(s.weight.x, expected, 1e-4f * expected);
    ASSERT_NEAR(s.weight.y, 0.5f * expected, 1e-4f * expected);
    ASSERT_GE(glm::dot(s.to_light, glm::normalize(l.position - p)), cos_max - 1e-5f);
    ASSERT_NEAR(glm::distance(p + s.distance * s.to_light, l.position), l.radius, 1e-3f);
  }
  // Far away it is the point light of the same intensity (ratio -> 1).
  const vec3 far(1000.0f, 0.0f, 0.0f);
  Light point = l;
  point.type = LightType::Point;
  EXPECT_NEAR(sample_light_direction(l, far, vec2(0.5f)).weight.x / sample_light(point, far).radiance.x, 1.0f, 1e-5f);
  // Inside: its radiance from every direction, up to its surface.
  const LightDirectionSample inside = sample_light_direction(l, l.position + vec3(0.5f, 0.0f, 0.0f), vec2(0.2f, 0.9f));
  EXPECT_NEAR(inside.weight.x, 4.0f * l.intensity / (l.radius * l.radius), 1e-5f);
  EXPECT_NEAR(glm::distance(l.position + vec3(0.5f, 0.0f, 0.0f) + inside.distance * inside.to_light, l.position),
              l.radius, 1e-4f);
}

// On the axis of a Lambertian disk of radiance L_d = 8 I / r^2 at height h
// the integral of radiance over directions is 2 pi L_d (1 - h / sqrt(h^2 + r^2)).
TEST(LightSampling, DiskLightIntegratesItsRadianceOnItsEmittingSideOnly) {
  Light l = make_light(LightType::Disk);
  l.position = vec3(0.0f, 0.0f, 10.0f);
  l.direction = vec3(0.0f, 0.0f, -1.0f);  // emits downward
  l.radius = 3.0f;
  const float h = 4.0f;
  const vec3 p(0.0f, 0.0f, 10.0f - h);
  const double expected =
      8.0 * l.intensity / (l.radius * l.radius) * 2.0 * kPi * (1.0 - h / std::hypot(h, l.radius)) / (4.0 * kPi);
  Pcg32 rng(11);
  const int n = 200000;
  double sum = 0.0, sum2 = 0.0;
  for (int i = 0; i < n; ++i) {
    const LightDirectionSample s = sample_light_direction(l, p, next2(rng));
    sum += s.weight.x;
    sum2 += double(s.weight.x) * s.weight.x;
    ASSERT_NEAR(p.z + s.distance * s.to_light.z, l.position.z, 1e-3f);  // lands on the disk
  }
  const double mean = sum / n;
  const double standard_error = std::sqrt((sum2 / n - mean * mean) / n);
  EXPECT_NEAR(mean, expected, 4.0 * standard_error);
  // Behind the disk: nothing.
  EXPECT_EQ(sample_light_direction(l, vec3(0.0f, 0.0f, 12.0f), vec2(0.3f)).weight, vec3(0.0f));
  // Far along the axis it is the point light's hemisphere: 2 I cos / d^2.
  const vec3 far(0.0f, 0.0f, -990.0f);
  EXPECT_NEAR(sample_light_direction(l, far, vec2(0.4f, 0.1f)).weight.x, 2.0f * l.intensity / (1000.0f * 1000.0f),
              1e-4f * 2.0f * l.intensity / (1000.0f * 1000.0f));
}

TEST(LightSampling, UniformDistantLightFillsItsCone) {
  Light l = make_light(LightType::Distant);
  l.direction = glm::normalize(vec3(0.2f, -0.3f, -1.0f));
  l.angle_deg = 20.0f;
  const float cos_max = std::cos(glm::radians(l.angle_deg));
  Pcg32 rng(13);
  const int n = 50000;
  double mean_cos = 0.0;
  for (int i = 0; i < n; ++i) {
    const LightDirectionSample s = sample_light_direction(l, vec3(0.0f), next2(rng));
    const float c = glm::dot(s.to_light, -l.direction);
    ASSERT_GE(c, cos_max - 1e-5f);
    ASSERT_EQ(s.weight, l.color * l.intensity);  // same power as a directional light
    ASSERT_EQ(s.distance, kInfinity);
    mean_cos += c;
  }
  // Uniform in solid angle: cos is uniform on [cos_max, 1].
  EXPECT_NEAR(mean_cos / n, 0.5 * (1.0 + cos_max), 4.0 * (1.0 - cos_max) / std::sqrt(12.0 * n));
  l.angle_deg = 0.0f;
  EXPECT_NEAR(glm::distance(sample_light_direction(l, vec3(0.0f), vec2(0.9f)).to_light, -l.direction), 0.0f, 1e-6f);
}

// Patel et al. 2013's Gaussian light: offsets on the virtual light plane
// (unit distance, perpendicular to the centre) are N(0, tan(angle)^2) per axis.
TEST(LightSampling, GaussianDistantLightIsGaussianOnTheVirtualLightPlane) {
  Light l = make_light(LightType::Distant);
  l.profile = LightProfile::Gaussian;
  l.direction = glm::normalize(vec3(-0.5f, 0.1f, -1.0f));
  l.angle_deg = 8.0f;
  const vec3 centre = -l.direction;
  vec3 t, b;
  orthonormal_basis(centre, t, b);
  Pcg32 rng(17);
  const int n = 50000;
  double sx = 0.0, sy = 0.0, sxx = 0.0, syy = 0.0, sxy = 0.0;
  for (int i = 0; i < n; ++i) {
    const vec3 w = sample_light_direction(l, vec3(0.0f), next2(rng)).to_light;
    const double x = glm::dot(w, t) / glm::dot(w, centre);
    const double y = glm::dot(w, b) / glm::dot(w, centre);
    sx += x, sy += y, sxx += x * x, syy += y * y, sxy += x * y;
  }
  const double variance = std::pow(std::tan(glm::radians(l.angle_deg)), 2.0);
  // Standard error of a variance estimate: variance * sqrt(2 / n) ~ 0.6%.
  EXPECT_NEAR(sxx / n, variance, 5.0 * variance * std::sqrt(2.0 / n));
  EXPECT_NEAR(syy / n, variance, 5.0 * variance * std::sqrt(2.0 / n));
  EXPECT_NEAR(sxy / n, 0.0, 5.0 * variance / std::sqrt(double(n)));
  EXPECT_NEAR(sx / n, 0.0, 5.0 * std::sqrt(variance / n));
  EXPECT_NEAR(sy / n, 0.0, 5.0 * std::sqrt(variance / n));
}

// The light frame (light.h): a is world +x made orthogonal to c, b =
// cross(c, a), (a, b, c) right-handed; +y replaces +x within 1 degree of +-x;
// rotation turns a toward b about c.
TEST(LightSampling, DistantLightFrameIsGramSchmidtOfXThenRotated) {
  vec3 a, b;
  distant_light_frame(vec3(0.0f, 0.0f, 1.0f), 0.0f, a, b);  // a light overhead
  EXPECT_NEAR(glm::distance(a, vec3(1.0f, 0.0f, 0.0f)), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::distance(b, vec3(0.0f, 1.0f, 0.0f)), 0.0f, 1e-6f);
  distant_light_frame(vec3(0.0f, 0.0f, 1.0f), 90.0f, a, b);  // counter-clockwise seen from the light
  EXPECT_NEAR(glm::distance(a, vec3(0.0f, 1.0f, 0.0f)), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::distance(b, vec3(-1.0f, 0.0f, 0.0f)), 0.0f, 1e-6f);
  Pcg32 rng(23);
  for (int i = 0; i < 200; ++i) {
    const vec3 c = sample_uniform_sphere(next2(rng));
    const float rot = 360.0f * rng.next_float() - 180.0f;
    if (std::abs(c.x) > 0.9998f) continue;  // the +y case, checked below
    vec3 a0, b0;
    distant_light_frame(c, 0.0f, a0, b0);
    distant_light_frame(c, rot, a, b);
    // Unrotated a: +x minus its component along c, normalised (and so the
    // unit vector perpendicular to c with the largest x).
    const vec3 gx = vec3(1.0f, 0.0f, 0.0f) - c.x * c;
    EXPECT_NEAR(glm::distance(a0, gx / glm::length(gx)), 0.0f, 1e-4f);
    EXPECT_NEAR(glm::dot(glm::cross(a0, b0), c), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::length(a), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(a, c), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(glm::cross(a, b), c), 1.0f, 1e-5f);
    const float r = glm::radians(rot);
    EXPECT_NEAR(glm::dot(a, a0), std::cos(r), 1e-5f);
    EXPECT_NEAR(glm::dot(a, b0), std::sin(r), 1e-5f);
  }
  // Along -x: Gram-Schmidt of +y; b = cross(-x, y) = -z.
  distant_light_frame(vec3(-1.0f, 0.0f, 0.0f), 0.0f, a, b);
  EXPECT_NEAR(glm::distance(a, vec3(0.0f, 1.0f, 0.0f)), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::distance(b, vec3(0.0f, 0.0f, -1.0f)), 0.0f, 1e-6f);
}

// An anisotropic, rotated Gaussian light: offsets (x, y) on the virtual
// light plane, in the unrotated frame, have covariance
// R diag(tan^2 ax, tan^2 ay) R^T and mean 0.
TEST(LightSampling, AnisotropicGaussianLightHasTheRotatedCovariance) {
  Light l = make_light(LightType::Distant);
  l.profile = LightProfile::Gaussian;
  l.direction = glm::normalize(vec3(0.3f, -0.4f, -1.0f));
  l.angle_deg = 3.0f;
  l.angle_y_deg = 12.0f;
  l.rotation_deg = 35.0f;
  const vec3 centre = -l.direction;
  vec3 a0, b0;
  distant_light_frame(centre, 0.0f, a0, b0);
  Pcg32 rng(29);
  const int n = 50000;
  double sx = 0.0, sy = 0.0, sxx = 0.0, syy = 0.0, sxy = 0.0;
  for (int i = 0; i < n; ++i) {
    const LightDirectionSample s = sample_light_direction(l, vec3(0.0f), next2(rng));
    ASSERT_EQ(s.weight, l.color * l.intensity);
    const vec3 w = s.to_light;
    const double x = glm::dot(w, a0) / glm::dot(w, centre);
    const double y = glm::dot(w, b0) / glm::dot(w, centre);
    sx += x, sy += y, sxx += x * x, syy += y * y, sxy += x * y;
  }
  const double vx = std::pow(std::tan(glm::radians(3.0)), 2.0), vy = std::pow(std::tan(glm::radians(12.0)), 2.0);
  const double c = std::cos(glm::radians(35.0)), si = std::sin(glm::radians(35.0));
  const double exx = c * c * vx + si * si * vy, eyy = si * si * vx + c * c * vy, exy = c * si * (vx - vy);
  // Standard error of a second-moment estimate E[x y] of a zero-mean normal
  // pair: sqrt((Sxx Syy + Sxy^2) / n); 5 of them (~0.7% relative here).
  auto tol = [&](double s1, double s2, double s12) { return 5.0 * std::sqrt((s1 * s2 + s12 * s12) / n); };
  EXPECT_NEAR(sxx / n, exx, tol(exx, exx, exx));
  EXPECT_NEAR(syy / n, eyy, tol(eyy, eyy, eyy));
  EXPECT_NEAR(sxy / n, exy, tol(exx, eyy, exy));
  EXPECT_NEAR(sx / n, 0.0, 5.0 * std::sqrt(exx / n));
  EXPECT_NEAR(sy / n, 0.0, 5.0 * std::sqrt(eyy / n));
  // A spread of 0 along x: every offset lies on the rotated y axis.
  l.angle_deg = 0.0f;
  vec3 a, b;
  distant_light_frame(centre, l.rotation_deg, a, b);
  for (int i = 0; i < 100; ++i) {
    const vec3 w = sample_light_direction(l, vec3(0.0f), next2(rng)).to_light;
    ASSERT_NEAR(glm::dot(w, a), 0.0f, 1e-6f);
  }
}

// Setting angle_y_deg = angle_deg (any rotation) is the isotropic light,
// sample for sample: orthonormal_basis(c) and the same Box-Muller offset.
TEST(LightSampling, IsotropicGaussianLightIsUnchangedByTheNewKeys) {
  Light l = make_light(LightType::Distant);
  l.profile = LightProfile::Gaussian;
  l.direction = glm::normalize(vec3(-0.5f, 0.1f, -1.0f));
  l.angle_deg = 8.0f;
  Light same = l;
  same.angle_y_deg = 8.0f;
  same.rotation_deg = 40.0f;
  vec3 t, b;
  orthonormal_basis(-l.direction, t, b);
  const float s = std::tan(glm::radians(8.0f));
  Pcg32 rng(31);
  for (int i = 0; i < 100; ++i) {
    const vec2 u = next2(rng);
    const vec3 w = sample_light_direction(l, vec3(0.0f), u).to_light;
    const float r = s * std::sqrt(-2.0f * std::log(1.0f - u.x));
    const float phi = 2.0f * kPi * u.y;
    const vec3 expected = glm::normalize(-l.direction + r * (std::cos(phi) * t + std::sin(phi) * b));
    ASSERT_NEAR(glm::distance(w, expected), 0.0f, 1e-6f);
    ASSERT_EQ(sample_light_direction(same, vec3(0.0f), u).to_light, w);
  }
}

TEST(LightSampling, EnvironmentIsUniformOverTheSphere) {
  const Light l = make_light(LightType::Environment);
  Pcg32 rng(19);
  const int n = 50000;
  dvec3 mean(0.0);
  double z2 = 0.0;
  for (int i = 0; i < n; ++i) {
    const LightDirectionSample s = sample_light_direction(l, vec3(0.0f), next2(rng));
    ASSERT_EQ(s.weight, l.color * l.intensity);  // radiance I * colour over pdf 1 / (4 pi), in 4 pi units
    mean += dvec3(s.to_light);
    z2 += double(s.to_light.z) * s.to_light.z;
  }
  mean /= double(n);
  EXPECT_LT(glm::length(mean), 4.0 * std::sqrt(1.0 / (3.0 * n)) * std::sqrt(3.0));
  EXPECT_NEAR(z2 / n, 1.0 / 3.0, 4.0 * std::sqrt(4.0 / 45.0 / n));  // Var(z^2) = 1/5 - 1/9
}

TEST(LightSampling, CosineHemisphereHasMeanCosineTwoThirds) {
  Pcg32 rng(23);
  const vec3 n = glm::normalize(vec3(1.0f, 2.0f, -0.5f));
  const int count = 50000;
  double sum = 0.0;
  for (int i = 0; i < count; ++i) {
    const float c = glm::dot(sample_cosine_hemisphere(n, next2(rng)), n);
    ASSERT_GE(c, 0.0f);
    sum += c;
  }
  // pdf cos / pi: E[cos] = 2/3, Var = 1/2 - 4/9.
  EXPECT_NEAR(sum / count, 2.0 / 3.0, 4.0 * std::sqrt((0.5 - 4.0 / 9.0) / count));
}

}  // namespace
}  // namespace penumbra

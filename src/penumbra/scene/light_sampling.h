#pragma once
// Monte Carlo sampling of every light type (light.h) as a Monte Carlo
// renderer needs it: a direction toward the light drawn from a density that
// follows the light's radiance, with the weight radiance / pdf. Together the
// samples integrate the light's radiance over the sphere of directions
// exactly as light.h defines it (unit tests check each integral).
//
// Weights are expressed in the units of LightSample::radiance: physically
// radiance / pdf(solid angle) / (4 pi), so a directional light of intensity
// I gives I * colour as in sample_light(), and a point light I * colour / d^2
// (DESIGN-NOTES.md "Light units": a light of intensity I delivers 4 pi I).
// A volume sample then scatters phase_hg_4pi(g, cos) * weight * T and a
// plane colour * cos * weight * T, the same formulas the shared lighting
// code uses with the light's centre.
//
// What each light's radiance is (derived from light.h's power statements):
//   distant, uniform   constant over the cone of half-angle `angle_deg`
//   distant, gaussian  directions normalize(c + x a + y b), c the central
//                      direction toward the light, (a, b) its light frame
//                      (distant_light_frame in light.h, rotation included),
//                      x ~ N(0, sx^2) and y ~ N(0, sy^2) independent on the
//                      plane at unit distance perpendicular to c, with
//                      sx = tan(angle_deg), sy = tan(angle_y_deg): a Gaussian
//                      light on the virtual light plane (Patel et al. 2013,
//                      section 3.2) whose offsets have the covariance
//                      R diag(sx^2, sy^2) R^T in the unrotated frame; its
//                      mean direction maps to tan(omega) as in the paper.
//                      Isotropic lights keep the basis orthonormal_basis(c)
//                      (the same samples as before anisotropy existed; any
//                      frame gives the same distribution)
//   sphere             uniform radiance 4 I / r^2 on a sphere of radius r
//                      (its power 16 pi^2 I equals the point light's)
//   disk               one-sided Lambertian, radiance 8 I / r^2 (power
//                      8 pi^2 I, a point light's power into a hemisphere)
//   environment        radiance I * colour from every direction
#include "penumbra/base/math.h"
#include "penumbra/scene/light.h"

namespace penumbra {

// Unit vectors t, b with (t, b, n) right-handed and orthonormal, for a unit n
// (Duff et al., "Building an Orthonormal Basis, Revisited", JCGT 6(1), 2017).
PENUMBRA_HD inline void orthonormal_basis(vec3 n, vec3& t, vec3& b) {
  const float sign = n.z >= 0.0f ? 1.0f : -1.0f;
  const float a = -1.0f / (sign + n.z);
  const float c = n.x * n.y * a;
  t = vec3(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
  b = vec3(c, sign + n.y * n.y * a, -n.y);
}

// The direction with cosine `cos_theta` to `axis` and azimuth 2 pi u.
PENUMBRA_HD inline vec3 direction_about(vec3 axis, float cos_theta, float u) {
  vec3 t, b;
  orthonormal_basis(axis, t, b);
  const float sin_theta = glm::sqrt(glm::max(0.0f, 1.0f - cos_theta * cos_theta));
  const float phi = 2.0f * kPi * u;
  return cos_theta * axis + sin_theta * (glm::cos(phi) * t + glm::sin(phi) * b);
}

// Uniform on the unit sphere (pdf 1 / (4 pi)).
PENUMBRA_HD inline vec3 sample_uniform_sphere(vec2 u) {
  const float z = 1.0f - 2.0f * u.x;
  const float r = glm::sqrt(glm::max(0.0f, 1.0f - z * z));
  const float phi = 2.0f * kPi * u.y;
  return vec3(r * glm::cos(phi), r * glm::sin(phi), z);
}

// Uniform over the cone about `axis` whose 1 - cos(half-angle) is
// `one_minus_cos_max` (passed in that form so small cones keep precision).
PENUMBRA_HD inline vec3 sample_uniform_cone(vec3 axis, float one_minus_cos_max, vec2 u) {
  return direction_about(axis, 1.0f - u.x * one_minus_cos_max, u.y);
}

// Cosine-weighted on the hemisphere about `normal` (pdf cos / pi).
PENUMBRA_HD inline vec3 sample_cosine_hemisphere(vec3 normal, vec2 u) {
  return direction_about(normal, glm::sqrt(1.0f - u.x), u.y);
}

// A sampled direction toward a light.
struct LightDirectionSample {
  vec3 to_light{0.0f, 0.0f, 1.0f};  // unit, from the shaded point toward the light
  float distance = kInfinity;       // to the sampled point on the light; +inf at infinity
  vec3 weight{0.0f};                // radiance / pdf / (4 pi); 0 when the point is not lit
};

// One direction toward `light` as seen from p, from two uniform numbers in
// [0, 1). Exact (zero-variance weight) for directional, point and distant
// lights; sphere lights are sampled uniformly in the solid angle they
// subtend, disks uniformly over their area, environments uniformly over the
// sphere.
PENUMBRA_HD inline LightDirectionSample sample_light_direction(const Light& light, vec3 p, vec2 u) {
  LightDirectionSample s;
  const vec3 power = light.color * light.intensity;
  switch (light.type) {
    case LightType::Directional:
      s.to_light = -light.direction;
      s.weight = power;
      return s;
    case LightType::Distant: {
      const vec3 centre = -light.direction;
      s.weight = power;
      if (light.profile == LightProfile::Uniform) {
        if (light.angle_deg <= 0.0f) {
          s.to_light = centre;
        } else {
          const float half_sin = glm::sin(0.5f * glm::radians(light.angle_deg));
          s.to_light = sample_uniform_cone(centre, 2.0f * half_sin * half_sin, u);  // 1 - cos = 2 sin^2(a / 2)
        }
        return s;
      }
      const vec2 spread = gaussian_light_spreads(light);
      if (spread.x <= 0.0f && spread.y <= 0.0f) {
        s.to_light = centre;
        return s;
      }
      // Box-Muller: two independent unit normals (r cos phi, r sin phi),
      // scaled per axis of the light frame.
      const float r = glm::sqrt(-2.0f * glm::log(1.0f - u.x));
      const float phi = 2.0f * kPi * u.y;
      vec3 t, b;
      if (spread.x == spread.y) {
        orthonormal_basis(centre, t, b);
        s.to_light = glm::normalize(centre + (spread.x * r) * (glm::cos(phi) * t + glm::sin(phi) * b));
      } else {
        distant_light_frame(centre, light.rotation_deg, t, b);
        s.to_light = glm::normalize(centre + (spread.x * r * glm::cos(phi)) * t + (spread.y * r * glm::sin(phi)) * b);
      }
      return s;
    }
    case LightType::Environment:
      s.to_light = sample_uniform_sphere(u);
      s.weight = power;  // radiance I * colour over pdf 1 / (4 pi), divided by 4 pi
      return s;
    case LightType::Point:
    case LightType::Sphere:
    case LightType::Disk: break;
  }
  const vec3 d = light.position - p;
  const float dist2 = glm::dot(d, d);
  const float r = light.radius;
  if (light.type == LightType::Sphere && r > 0.0f) {
    const float r2 = r * r;
    if (dist2 <= r2) {
      // Inside the sphere: its radiance 4 I / r^2 arrives from every direction.
      s.to_light = sample_uniform_sphere(u);
      const float b = glm::dot(s.to_light, d);
      s.distance = b + glm::sqrt(glm::max(0.0f, b * b + r2 - dist2));
      s.weight = power * (4.0f / r2);
      return s;
    }
    const float dist = glm::sqrt(dist2);
    const vec3 axis = d / dist;
    const float sin2_max = r2 / dist2;
    const float cos_max = glm::sqrt(glm::max(0.0f, 1.0f - sin2_max));
    s.to_light = sample_uniform_cone(axis, sin2_max / (1.0f + cos_max), u);
    const float b = glm::dot(s.to_light, d);
    s.distance = glm::max(0.0f, b - glm::sqrt(glm::max(0.0f, r2 - (dist2 - b * b))));
    // (4 I / r^2) * 2 pi (1 - cos_max) / (4 pi) = 2 I / (d^2 (1 + cos_max)).
    s.weight = power * (2.0f / (dist2 * (1.0f + cos_max)));
    return s;
  }
  if (light.type == LightType::Disk && r > 0.0f) {
    vec3 t, b;
    orthonormal_basis(light.direction, t, b);
    const float radial = r * glm::sqrt(u.x);
    const float phi = 2.0f * kPi * u.y;
    const vec3 q = light.position + radial * (glm::cos(phi) * t + glm::sin(phi) * b);
    const vec3 w = q - p;
    const float w2 = glm::max(glm::dot(w, w), 1e-12f);
    s.distance = glm::sqrt(w2);
    s.to_light = w / s.distance;
    // (8 I / r^2) cos_emit (pi r^2) / w^2 / (4 pi) = 2 I cos_emit / w^2.
    const float cos_emit = glm::max(0.0f, -glm::dot(s.to_light, light.direction));
    s.weight = power * (2.0f * cos_emit / w2);
    return s;
  }
  // Point lights, and spheres and disks of radius 0 (which are point lights).
  const LightSample centre = sample_light(light, p);
  s.to_light = centre.to_light;
  s.distance = centre.distance;
  s.weight = centre.radiance;
  return s;
}

}  // namespace penumbra

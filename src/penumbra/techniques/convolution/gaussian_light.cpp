#include "penumbra/techniques/convolution/gaussian_light.h"

#include <cmath>

namespace penumbra {

glm::mat2 rotated_covariance(float sigma_x2, float sigma_y2, float rotation_deg) {
  const float a = glm::radians(rotation_deg);
  const glm::mat2 r(std::cos(a), std::sin(a), -std::sin(a), std::cos(a));  // columns
  const glm::mat2 d(sigma_x2, 0.0f, 0.0f, sigma_y2);
  return r * d * glm::transpose(r);
}

PrincipalAxes principal_axes(const glm::mat2& c) {
  const float sxx = c[0][0], syy = c[1][1], sxy = 0.5f * (c[0][1] + c[1][0]);
  const float mean = 0.5f * (sxx + syy);
  const float diff = 0.5f * (sxx - syy);
  const float radius = std::sqrt(diff * diff + sxy * sxy);
  PrincipalAxes p;
  p.var_x = glm::max(mean + radius, 0.0f);
  p.var_y = glm::max(mean - radius, 0.0f);
  p.angle = 0.5f * std::atan2(2.0f * sxy, sxx - syy);
  return p;
}

GaussianLight gaussian_light(const Light& light, const CameraView& camera, vec3 box_center,
                             const LightOverride& o) {
  vec3 d = light.at_infinity() ? light.direction : box_center - light.position;
  if (!(glm::length(d) > 0.0f)) d = camera.forward;
  d = glm::normalize(d);
  GaussianLight g;
  // The virtual light plane cannot hold lights at or beyond 90 degrees from
  // the view direction (mu = tan(tilt) diverges): clamp the tilt to 85
  // degrees, keeping the lateral direction (a light straight at the viewer
  // becomes one from straight behind).
  const float max_tilt = glm::radians(85.0f);
  vec2 d_lat(glm::dot(d, camera.right), glm::dot(d, camera.up));
  const float cos_view = glm::dot(d, camera.forward);
  if (!(cos_view >= std::cos(max_tilt))) {
    const float len = glm::length(d_lat);
    d_lat = len > 1e-6f ? d_lat / len * std::sin(max_tilt) : vec2(0.0f);
    d = glm::normalize(d_lat.x * camera.right + d_lat.y * camera.up +
                       (len > 1e-6f ? std::cos(max_tilt) : 1.0f) * camera.forward);
    d_lat = vec2(glm::dot(d, camera.right), glm::dot(d, camera.up));
  }
  g.cos_view = glm::dot(d, camera.forward);
  g.mu = d_lat / g.cos_view;
  if (o.sigma_x2 >= 0.0f) {
    g.covariance = rotated_covariance(o.sigma_x2, glm::max(o.sigma_y2, 0.0f), o.rotation_deg);
    return g;
  }
  vec2 variance(0.0f);  // along the light frame's (a, b)
  if (light.type == LightType::Distant) {
    const float tx = std::tan(glm::radians(glm::clamp(light.angle_deg, 0.0f, 89.0f)));
    if (light.profile == LightProfile::Gaussian) {
      const float ty = std::tan(glm::radians(glm::clamp(light.spread_y_deg(), 0.0f, 89.0f)));
      variance = vec2(tx * tx, ty * ty);
    } else {
      variance = vec2(0.25f * tx * tx);
    }
  } else if ((light.type == LightType::Sphere || light.type == LightType::Disk) && light.radius > 0.0f) {
    // The disk the light subtends from the box centre, at distance D from
    // its centre: tan = r / sqrt(D^2 - r^2), variance tan^2 / 4 per axis as
    // for a uniform cone (a disk as if seen face on).
    const float dist = glm::length(box_center - light.position), r = light.radius;
    const float t = dist > 1.001f * r ? r / std::sqrt(dist * dist - r * r) : std::tan(glm::radians(89.0f));
    variance = vec2(0.25f * t * t);
  }
  if (variance.x <= 0.0f && variance.y <= 0.0f) return g;
  // Jacobian of w -> lateral slope of (d + w) at w = 0, for w in the plane of
  // d, applied to the light frame's axes (frame of the direction toward the
  // light, -d; the sign of w does not change a covariance).
  vec3 a, b;
  distant_light_frame(-d, light.type == LightType::Distant ? light.rotation_deg : 0.0f, a, b);
  auto column = [&](vec3 w) {
    const vec2 w_lat(glm::dot(w, camera.right), glm::dot(w, camera.up));
    return w_lat / g.cos_view - d_lat * (glm::dot(w, camera.forward) / (g.cos_view * g.cos_view));
  };
  const glm::mat2 j(column(a), column(b));
  const glm::mat2 diag(variance.x, 0.0f, 0.0f, variance.y);
  g.covariance = j * diag * glm::transpose(j);
  return g;
}

}  // namespace penumbra

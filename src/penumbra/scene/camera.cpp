#include "penumbra/scene/camera.h"

#include "penumbra/base/error.h"

#include <fmt/format.h>

#include <cmath>

namespace penumbra {

void Camera::validate() const {
  for (const auto& [name, v] : {std::pair{"camera.eye", eye}, {"camera.target", target}, {"camera.up", up}}) {
    if (!is_finite(v.x) || !is_finite(v.y) || !is_finite(v.z)) throw InvalidScene(name, "must be finite");
  }
  const vec3 d = target - eye;
  // Components near the float limit overflow the direction (1e38 - -1e38).
  if (!is_finite(glm::length(d))) throw InvalidScene("camera.eye", "is too far from camera.target: the distance overflows");
  if (glm::length(d) <= 0.0f) throw InvalidScene("camera.target", "must differ from camera.eye");
  if (glm::length(up) <= 0.0f) throw InvalidScene("camera.up", "must not be the zero vector");
  if (glm::length(glm::cross(glm::normalize(d), glm::normalize(up))) < 1e-4f) {
    throw InvalidScene("camera.up", "is parallel to the view direction (eye -> target)");
  }
  if (projection == Projection::Perspective && !(fov_deg > 0.0f && fov_deg < 180.0f)) {
    throw InvalidScene("camera.fov_deg", fmt::format("must be in (0, 180), got {}", fov_deg));
  }
  if (projection == Projection::Orthographic && !(ortho_height > 0.0f && is_finite(ortho_height))) {
    throw InvalidScene("camera.height", fmt::format("must be positive, got {}", ortho_height));
  }
}

CameraView Camera::view() const {
  validate();
  CameraView v;
  v.eye = eye;
  v.forward = glm::normalize(target - eye);
  v.right = glm::normalize(glm::cross(v.forward, up));
  v.up = glm::cross(v.right, v.forward);
  v.orthographic = projection == Projection::Orthographic;
  v.half_height = v.orthographic ? 0.5f * ortho_height : std::tan(0.5f * glm::radians(fov_deg));
  return v;
}

void Camera::orbit(float azimuth_deg, float elevation_deg) {
  const vec3 axis = glm::normalize(up);
  vec3 offset = eye - target;
  const float radius = glm::length(offset);
  // Spherical coordinates about `axis`.
  const vec3 along = glm::dot(offset, axis) * axis;
  const vec3 across = offset - along;
  vec3 e0 = glm::length(across) > 1e-6f * radius ? glm::normalize(across) : glm::normalize(glm::cross(axis, vec3(1, 0, 0)));
  const vec3 e1 = glm::cross(axis, e0);
  float elevation = std::asin(glm::clamp(glm::dot(offset, axis) / radius, -1.0f, 1.0f));
  const float azimuth = glm::radians(azimuth_deg);
  elevation = glm::clamp(elevation + glm::radians(elevation_deg), glm::radians(-89.0f), glm::radians(89.0f));
  const vec3 horizontal = std::cos(azimuth) * e0 + std::sin(azimuth) * e1;
  offset = radius * (std::cos(elevation) * horizontal + std::sin(elevation) * axis);
  eye = target + offset;
}

Camera Camera::framing(const Box3& box, vec3 direction, vec3 up, float fov_deg) {
  Camera c;
  c.target = box.center();
  c.up = up;
  c.fov_deg = fov_deg;
  const float radius = 0.5f * glm::length(box.extent());
  const float distance = radius / std::sin(0.5f * glm::radians(fov_deg));
  c.eye = c.target + glm::normalize(direction) * std::max(distance, 1e-3f);
  c.ortho_height = 2.0f * radius;
  return c;
}

}  // namespace penumbra

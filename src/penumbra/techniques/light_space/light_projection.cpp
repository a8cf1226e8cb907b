#include "penumbra/techniques/light_space/light_projection.h"

#include <algorithm>
#include <array>

namespace penumbra {
namespace {

// Unit u, v completing w to a right-handed frame (Duff et al., JCGT 6(1),
// 2017), so the frame does not jump as a light moves.
LightFace face_looking_along(vec3 w) {
  const float sign = w.z >= 0.0f ? 1.0f : -1.0f;
  const float a = -1.0f / (sign + w.z);
  const float b = w.x * w.y * a;
  LightFace f;
  f.u = vec3(1.0f + sign * w.x * w.x * a, sign * b, -sign * w.x);
  f.v = vec3(b, sign + w.y * w.y * a, -w.y);
  f.w = w;
  return f;
}

std::array<vec3, 8> corners(const Box3& box) {
  std::array<vec3, 8> c;
  for (int i = 0; i < 8; ++i) {
    c[i] = vec3(i & 1 ? box.upper.x : box.lower.x, i & 2 ? box.upper.y : box.lower.y,
                i & 4 ? box.upper.z : box.lower.z);
  }
  return c;
}

// Grows a window half-size by a few texels so the box's silhouette (and the
// bilinear / filter footprint around it) stays inside the map.
float with_margin(float half, int resolution) { return half * (1.0f + 4.0f / float(resolution)); }

LightProjection cube_map(vec3 position, int resolution) {
  LightProjection p;
  p.kind = LightProjectionKind::Perspective;
  p.resolution = std::max(1, resolution / 2);
  p.face_count = 6;
  p.origin = position;
  p.window_center = vec2(0.0f);
  p.window_half = 1.0f;  // exactly 90 degrees: every direction falls on the face of its major axis
  for (int axis = 0; axis < 3; ++axis) {
    for (int s = 0; s < 2; ++s) {
      vec3 w(0.0f);
      w[axis] = s == 0 ? 1.0f : -1.0f;
      p.faces[2 * axis + s] = face_looking_along(w);
    }
  }
  return p;
}

}  // namespace

LightProjection make_light_projection(const Light& light, const Box3& box, int resolution) {
  LightProjection p;
  p.resolution = resolution;
  if (light.type == LightType::Environment) return p;
  const std::array<vec3, 8> box_corners = corners(box);
  if (light.at_infinity()) {
    p.kind = LightProjectionKind::Orthographic;
    p.face_count = 1;
    p.faces[0] = face_looking_along(glm::normalize(light.direction));
    const float radius = 0.5f * glm::length(box.extent());
    p.origin = box.center() - (radius + 1.0f) * p.faces[0].w;
    float half = 0.0f;
    for (const vec3& c : box_corners) {
      const vec3 d = c - p.origin;
      half = std::max({half, std::abs(glm::dot(d, p.faces[0].u)), std::abs(glm::dot(d, p.faces[0].v))});
    }
    p.window_center = vec2(0.0f);  // the box is centrally symmetric about its centre, which lies on the axis
    p.window_half = with_margin(std::max(half, 1e-6f), resolution);
    return p;
  }
  const vec3 to_center = box.center() - light.position;
  const float distance = glm::length(to_center);
  if (!(distance > 0.0f)) return cube_map(light.position, resolution);
  p.kind = LightProjectionKind::Perspective;
  p.face_count = 1;
  p.origin = light.position;
  p.faces[0] = face_looking_along(to_center / distance);
  const LightFace& f = p.faces[0];
  vec2 lo(kInfinity), hi(-kInfinity);
  for (const vec3& c : box_corners) {
    const vec3 d = c - light.position;
    const float dw = glm::dot(d, f.w);
    // A corner (nearly) beside or behind the light: no single frustum holds the box.
    if (!(dw > 1e-3f * glm::length(d))) return cube_map(light.position, resolution);
    const vec2 a = vec2(glm::dot(d, f.u), glm::dot(d, f.v)) / dw;
    lo = glm::min(lo, a);
    hi = glm::max(hi, a);
  }
  p.window_center = 0.5f * (lo + hi);
  const float half = with_margin(0.5f * std::max(hi.x - lo.x, hi.y - lo.y), resolution);
  if (half > kMaxPerspectiveHalfTangent) return cube_map(light.position, resolution);
  p.window_half = std::max(half, 1e-6f);
  return p;
}

}  // namespace penumbra

#include "penumbra/techniques/ipsvi/light_cache_projection.h"

#include "penumbra/base/error.h"

#include <array>

namespace penumbra {
namespace {

std::array<vec3, 8> box_corners(const Box3& box) {
  std::array<vec3, 8> corners;
  for (int i = 0; i < 8; ++i) {
    corners[i] = vec3(i & 1 ? box.upper.x : box.lower.x, i & 2 ? box.upper.y : box.lower.y,
                      i & 4 ? box.upper.z : box.lower.z);
  }
  return corners;
}

// Two unit vectors completing `axis` to a right-handed frame.
void complete_frame(vec3 axis, vec3& u, vec3& v) {
  const vec3 helper = glm::abs(axis.x) < 0.9f ? vec3(1.0f, 0.0f, 0.0f) : vec3(0.0f, 1.0f, 0.0f);
  u = glm::normalize(glm::cross(helper, axis));
  v = glm::cross(axis, u);
}

// A little margin so that points on the box faces stay inside the outer texels.
constexpr float kMargin = 1.02f;

}  // namespace

LightCacheProjection make_light_cache_projection(const Light& light, const Box3& box, int size) {
  if (size < 1) throw InvalidArgument("cache_size", "must be at least 1");
  LightCacheProjection p;
  p.size = size;
  const auto corners = box_corners(box);
  const float diagonal = glm::max(glm::length(box.extent()), 1e-6f);

  if (light.at_infinity()) {
    p.mapping = LightMapping::Orthographic;
    p.axis = glm::normalize(light.direction);
    complete_frame(p.axis, p.side_u, p.side_v);
    vec3 lo(kInfinity), hi(-kInfinity);
    for (const vec3& c : corners) {
      const vec3 q(glm::dot(c, p.side_u), glm::dot(c, p.side_v), glm::dot(c, p.axis));
      lo = glm::min(lo, q);
      hi = glm::max(hi, q);
    }
    const float extent = glm::max(glm::max(hi.x - lo.x, hi.y - lo.y), 1e-3f * diagonal) * kMargin;
    const vec2 center = 0.5f * (vec2(lo) + vec2(hi));
    const vec2 corner = center - vec2(0.5f * extent);
    p.origin = corner.x * p.side_u + corner.y * p.side_v + lo.z * p.axis;
    p.texels_per_unit = float(size) / extent;
    p.max_depth = hi.z - lo.z;
    return p;
  }

  p.origin = light.position;
  for (const vec3& c : corners) p.max_depth = glm::max(p.max_depth, glm::length(c - light.position));
  p.axis = glm::normalize(box.center() - light.position);
  // A frustum works while every corner lies well in front of the light;
  // otherwise (light inside or right beside the box) map all directions.
  bool frustum = !box.contains(light.position) && is_finite(p.axis.x);
  float tan_extent = 0.0f;
  if (frustum) {
    complete_frame(p.axis, p.side_u, p.side_v);
    for (const vec3& c : corners) {
      const vec3 q = c - light.position;
      const float z = glm::dot(q, p.axis);
      if (z < 0.3f * glm::length(q)) {  // beyond about 72 degrees off axis
        frustum = false;
        break;
      }
      tan_extent = glm::max(tan_extent, glm::max(glm::abs(glm::dot(q, p.side_u)), glm::abs(glm::dot(q, p.side_v))) / z);
    }
  }
  if (!frustum) {
    p.mapping = LightMapping::Octahedral;
    p.axis = vec3(0.0f, 0.0f, 1.0f);
    p.side_u = vec3(1.0f, 0.0f, 0.0f);
    p.side_v = vec3(0.0f, 1.0f, 0.0f);
    return p;
  }
  p.mapping = LightMapping::Perspective;
  p.tan_extent = glm::max(tan_extent * kMargin, 1e-6f);
  p.texels_per_unit = 0.5f * float(size) / p.tan_extent;
  return p;
}

}  // namespace penumbra

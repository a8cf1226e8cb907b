#include "penumbra/techniques/ipsvi/sweep_plan.h"

#include <algorithm>
#include <cmath>

namespace penumbra {
namespace {

// Homogeneous pixel position (X, Y, W) of a point (w = 1) or of a direction
// at infinity (w = 0) seen through the camera: pixel = (X, Y) / W.
vec3 homogeneous_pixel(const CameraView& c, int width, int height, vec3 q, bool direction) {
  const float aspect = float(width) / float(height);
  const float sx = glm::dot(q, c.right) / (c.half_height * aspect);
  const float sy = glm::dot(q, c.up) / c.half_height;
  if (c.orthographic) {
    const float w = direction ? 0.0f : 1.0f;
    return vec3((sx + w) * 0.5f * float(width), (w - sy) * 0.5f * float(height), w);
  }
  const float z = glm::dot(q, c.forward);
  return vec3((sx + z) * 0.5f * float(width), (z - sy) * 0.5f * float(height), z);
}

float smoothstep01(float x) {
  x = std::clamp(x, 0.0f, 1.0f);
  return x * x * (3.0f - 2.0f * x);
}

}  // namespace

ImageLight project_light(const CameraView& camera, int width, int height, const Light& light) {
  const bool direction = light.at_infinity();
  const vec3 q = direction ? -glm::normalize(light.direction) : light.position - camera.eye;
  const vec3 h = homogeneous_pixel(camera, width, height, q, direction);
  ImageLight out;
  const float extent = float(width + height);
  // s'_l farther than 10^4 image sizes: its lines are parallel to a pixel.
  if (std::abs(h.z) * 1e4f * extent <= std::abs(h.x) + std::abs(h.y) || h.z == 0.0f) {
    out.flow = LightFlow::Parallel;
    const vec2 d(-h.x, -h.y);  // the same for either sign of a vanishing w (see sweep_plan.h)
    // A light along the view direction has no image direction.
    const float across = glm::length(vec2(glm::dot(q, camera.right), glm::dot(q, camera.up)));
    out.direction = across > 1e-5f * glm::length(q) ? glm::normalize(d) : vec2(0.0f);
    return out;
  }
  out.flow = h.z > 0.0f ? LightFlow::Outward : LightFlow::Inward;
  out.position = vec2(h.x, h.y) / h.z;
  return out;
}

PixelRect projected_box_rect(const CameraView& camera, int width, int height, const Box3& box) {
  PixelRect full{0, 0, width, height};
  vec2 lo(kInfinity), hi(-kInfinity);
  for (int i = 0; i < 8; ++i) {
    const vec3 corner(i & 1 ? box.upper.x : box.lower.x, i & 2 ? box.upper.y : box.lower.y,
                      i & 4 ? box.upper.z : box.lower.z);
    const vec3 h = homogeneous_pixel(camera, width, height, corner - camera.eye, false);
    if (!(h.z > 1e-6f)) return full;
    const vec2 p = vec2(h.x, h.y) / h.z;
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  PixelRect r;
  r.x0 = int(std::clamp(std::floor(lo.x) - 1.0f, 0.0f, float(width)));
  r.y0 = int(std::clamp(std::floor(lo.y) - 1.0f, 0.0f, float(height)));
  r.x1 = int(std::clamp(std::ceil(hi.x) + 1.0f, 0.0f, float(width)));
  r.y1 = int(std::clamp(std::ceil(hi.y) + 1.0f, 0.0f, float(height)));
  return r;
}

float SweepZone::weight(vec2 p) const {
  if (!radial) return 1.0f;
  const float dx = p.x - light.x, dy = p.y - light.y;
  const float d_axis = axis == 0 ? dx : dy;
  // Pixels exactly on s'_l belong to the +x zone.
  const bool on_side = sign > 0 ? d_axis >= 0.0f : d_axis < 0.0f;
  if (!on_side) return 0.0f;
  const float phi = (dx == 0.0f && dy == 0.0f) ? 0.0f : glm::degrees(std::atan2(std::abs(dy), std::abs(dx)));
  const float weight_x = band_deg > 0.0f ? smoothstep01((45.0f + band_deg - phi) / (2.0f * band_deg))
                                         : (phi < 45.0f || (phi == 45.0f && axis == 0) ? 1.0f : 0.0f);
  if (axis == 1 && dx == 0.0f && dy == 0.0f) return 0.0f;
  return axis == 0 ? weight_x : 1.0f - weight_x;
}

bool SweepZone::path_crossing(vec2 p, int coordinate, float& across) const {
  const int other = 1 - axis;
  const float c = float(coordinate) + 0.5f;
  if (!radial) {
    if (direction[axis] == 0.0f) return false;
    across = p[other] + direction[other] / direction[axis] * (c - p[axis]);
    return true;
  }
  const float d = p[axis] - light[axis];
  const float d_next = c - light[axis];
  if (d == 0.0f || d * d_next <= 0.0f) return false;
  across = light[other] + (p[other] - light[other]) * (d_next / d);
  return true;
}

SweepPlan make_sweep_plan(const ImageLight& light, const PixelRect& rect, float band_deg, int parallel_axis_hint) {
  SweepPlan plan;
  plan.light = light;
  if (rect.empty()) return plan;
  const int lo[2] = {rect.x0, rect.y0};
  const int hi[2] = {rect.x1 - 1, rect.y1 - 1};

  if (light.flow == LightFlow::Parallel) {
    SweepZone zone;
    const vec2 d = light.direction;
    if (d == vec2(0.0f)) {
      zone.axis = parallel_axis_hint == 0 ? 0 : 1;
      zone.order = 1;
    } else {
      zone.axis = std::abs(d.x) >= std::abs(d.y) ? 0 : 1;
      zone.order = d[zone.axis] >= 0.0f ? 1 : -1;
    }
    zone.direction = d;
    const int a = zone.axis, o = 1 - a;
    for (int i = 0; i <= hi[a] - lo[a]; ++i) {
      const int c = zone.order > 0 ? lo[a] + i : hi[a] - i;
      zone.lines.push_back(SweepLine{c, lo[o], hi[o]});
    }
    plan.zones.push_back(std::move(zone));
    return plan;
  }

  const float slope = std::tan(glm::radians(45.0f + band_deg));
  for (int axis = 0; axis < 2; ++axis) {
    for (int sign : {1, -1}) {
      SweepZone zone;
      zone.axis = axis;
      zone.sign = sign;
      zone.radial = true;
      zone.light = light.position;
      zone.band_deg = band_deg;
      const int o = 1 - axis;
      const float s_a = light.position[axis], s_o = light.position[o];
      std::vector<SweepLine> lines;
      for (int c = lo[axis]; c <= hi[axis]; ++c) {
        const float dist = float(sign) * (float(c) + 0.5f - s_a);
        if (sign > 0 ? dist < 0.0f : dist <= 0.0f) continue;
        const float half = dist * slope;
        const int a0 = std::max(lo[o], int(std::ceil(s_o - half - 0.5f)));
        const int a1 = std::min(hi[o], int(std::floor(s_o + half - 0.5f)));
        if (a0 <= a1) lines.push_back(SweepLine{c, a0, a1});
      }
      if (lines.empty()) continue;
      // Outward: nearest s'_l first; inward: farthest first.
      const bool increasing = (sign > 0) == (light.flow == LightFlow::Outward);
      if (!increasing) std::reverse(lines.begin(), lines.end());
      zone.order = increasing ? 1 : -1;
      zone.lines = std::move(lines);
      plan.zones.push_back(std::move(zone));
    }
  }
  return plan;
}

}  // namespace penumbra

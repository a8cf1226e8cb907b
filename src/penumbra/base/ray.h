#pragma once
// Rays, boxes and the parameter intervals where a ray overlaps them.
#include "penumbra/base/math.h"

namespace penumbra {

struct Ray {
  vec3 origin;
  vec3 direction;  // unit length unless a caller says otherwise
  PENUMBRA_HD vec3 at(float t) const { return origin + t * direction; }
};

struct Box3 {
  vec3 lower{0.0f};
  vec3 upper{0.0f};
  PENUMBRA_HD vec3 center() const { return 0.5f * (lower + upper); }
  PENUMBRA_HD vec3 extent() const { return upper - lower; }
  PENUMBRA_HD bool contains(vec3 p) const {
    return p.x >= lower.x && p.y >= lower.y && p.z >= lower.z && p.x <= upper.x && p.y <= upper.y &&
           p.z <= upper.z;
  }
};

// A parameter range [t0, t1] along a ray; empty when t0 >= t1.
struct Interval {
  float t0 = 0.0f;
  float t1 = -1.0f;
  PENUMBRA_HD bool empty() const { return !(t0 < t1); }
  PENUMBRA_HD float length() const { return empty() ? 0.0f : t1 - t0; }
};

// Overlap of the ray with the box, restricted to [t_min, t_max]. Axis-parallel
// rays are handled explicitly so no 0 * inf NaN can appear.
PENUMBRA_HD inline Interval intersect_box(const Ray& ray, const Box3& box, float t_min, float t_max) {
  Interval r{t_min, t_max};
  for (int axis = 0; axis < 3; ++axis) {
    const float o = ray.origin[axis];
    const float d = ray.direction[axis];
    if (d == 0.0f) {
      if (o < box.lower[axis] || o > box.upper[axis]) return Interval{};
      continue;
    }
    const float inv = 1.0f / d;
    float t_near = (box.lower[axis] - o) * inv;
    float t_far = (box.upper[axis] - o) * inv;
    if (t_near > t_far) {
      const float tmp = t_near;
      t_near = t_far;
      t_far = tmp;
    }
    r.t0 = t_near > r.t0 ? t_near : r.t0;
    r.t1 = t_far < r.t1 ? t_far : r.t1;
  }
  return r;
}

// A clip plane [a, b, c, d] keeps the points with a x + b y + c z + d >= 0. The
// kept region of several planes is convex, so restricting a ray to it gives a
// single interval, exactly.
PENUMBRA_HD inline Interval clip_interval(const Ray& ray, const vec4* planes, int plane_count, Interval r) {
  for (int i = 0; i < plane_count; ++i) {
    const vec3 n(planes[i]);
    const float f0 = glm::dot(n, ray.origin) + planes[i].w;
    const float fd = glm::dot(n, ray.direction);
    if (fd == 0.0f) {
      if (f0 < 0.0f) return Interval{};
    } else if (fd > 0.0f) {
      r.t0 = glm::max(r.t0, -f0 / fd);
    } else {
      r.t1 = glm::min(r.t1, -f0 / fd);
    }
  }
  return r;
}

PENUMBRA_HD inline bool inside_clip_planes(vec3 p, const vec4* planes, int plane_count) {
  for (int i = 0; i < plane_count; ++i) {
    if (glm::dot(vec3(planes[i]), p) + planes[i].w < 0.0f) return false;
  }
  return true;
}

}  // namespace penumbra

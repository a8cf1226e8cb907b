#pragma once
// Rays, boxes and the parameter intervals where a ray overlaps them.
#include "penumbra/base/lanes.h"
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

// Lanes of points inside a box (Box3::contains for lanes).
template <class L>
PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Mask box_contains(const Box3& box, const typename L::Vec3& p) {
  return (p.x >= box.lower.x) & (p.y >= box.lower.y) & (p.z >= box.lower.z) & (p.x <= box.upper.x) &
         (p.y <= box.upper.y) & (p.z <= box.upper.z);
}

// Overlap [t0, t1] of rays o + t d with the box, restricted to [t_min, t_max]
// (t0 and t1 on entry), per lane; empty where !(t0 < t1). A zero direction
// component keeps that slab's bounds out of the arithmetic (no 0 * inf NaN);
// where the origin lies outside such a slab the lane gets the empty [0, -1],
// as do all misses of the scalar intersect_box, whose callers read t0 and t1.
template <class L>
PENUMBRA_HD PENUMBRA_FORCE_INLINE void box_overlap(const Box3& box, const typename L::Vec3& o,
                                                   const typename L::Vec3& d, typename L::Float& t0,
                                                   typename L::Float& t1) {
  using F = typename L::Float;
  const auto slab = [&](const F& oa, const F& da, float lo, float hi) {
    const auto parallel = da == F(0.0f);
    const F inv = F(1.0f) / select(parallel, F(1.0f), da);
    const F a = (F(lo) - oa) * inv;
    const F b = (F(hi) - oa) * inv;
    t0 = select(parallel, t0, max(t0, min(a, b)));
    t1 = select(parallel, t1, min(t1, max(a, b)));
    return parallel & ((oa < F(lo)) | (oa > F(hi)));
  };
  const auto miss = slab(o.x, d.x, box.lower.x, box.upper.x) | slab(o.y, d.y, box.lower.y, box.upper.y) |
                    slab(o.z, d.z, box.lower.z, box.upper.z);
  t0 = select(miss, F(0.0f), t0);
  t1 = select(miss, F(-1.0f), t1);
}

// The scalar ray's overlap with the box within [t_min, t_max].
PENUMBRA_HD inline Interval intersect_box(const Ray& ray, const Box3& box, float t_min, float t_max) {
  Interval r{t_min, t_max};
  box_overlap<ScalarLanes>(box, ray.origin, ray.direction, r.t0, r.t1);
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

// Lanes of points on the kept side of every clip plane (a . p + w >= 0, or NaN).
template <class L>
PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Mask inside_clip_planes(const typename L::Vec3& p, const vec4* planes,
                                                                      int plane_count) {
  typename L::Mask inside(true);
  for (int i = 0; i < plane_count; ++i) {
    inside = inside & !(dot(typename L::Vec3(vec3(planes[i])), p) + planes[i].w < 0.0f);
    if (none(inside)) break;
  }
  return inside;
}
PENUMBRA_HD inline bool inside_clip_planes(vec3 p, const vec4* planes, int plane_count) {
  return inside_clip_planes<ScalarLanes>(p, planes, plane_count);
}

}  // namespace penumbra

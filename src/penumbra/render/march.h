#pragma once
// The marching loop every technique shares (DESIGN.md 1): clip the ray to the
// volume box, the clip planes and the nearest opaque plane, walk the macrocell
// grid so empty space costs no samples, and composite front to back with
// opacity correction alpha = 1 - exp(-sigma_t * length) and early ray
// termination. A technique supplies only how a sample is lit (a Lighting type
// with sample() and plane(), see lighting.h).
//
// Sampling convention: the ray's interval [t0, t1] is cut into segments of the
// step ds (the last one shorter); segment k is represented by one sample at
// offset * length inside it (offset 0.5 = midpoint, or a per-pixel random
// value with jitter). Segment lengths add up to t1 - t0 exactly, so a
// homogeneous medium integrates to exp(-sigma_t (t1 - t0)) at any step.
#include "penumbra/base/ray.h"
#include "penumbra/render/render_view.h"

#include <cstdint>

namespace penumbra {

struct RayStats {
  std::uint64_t samples = 0;  // volume samples taken (trilinear lookups)
};

struct SamplePoint {
  vec3 world;     // world position
  vec3 index;     // index-space position
  float value;    // interpolated scalar
  vec3 color;     // TF colour
  float sigma_t;  // extinction per world unit
  vec3 ray_dir;   // unit direction of the viewing ray
};

struct PlaneHit {
  vec3 position;
  int plane;  // index into RenderView::planes
  vec3 ray_dir;
};

struct SampleGrid {
  float t0 = 0.0f;
  float t1 = 0.0f;
  float ds = 1.0f;
  float offset = 0.5f;
  int count = 0;

  PENUMBRA_HD SampleGrid(Interval iv, float step, float sample_offset)
      : t0(iv.t0), t1(iv.t1), ds(step), offset(sample_offset) {
    count = iv.empty() ? 0 : int(glm::ceil((iv.t1 - iv.t0) / step));
    if (count < 1 && !iv.empty()) count = 1;
  }
  PENUMBRA_HD float start(int k) const { return t0 + float(k) * ds; }
  PENUMBRA_HD float length(int k) const { return glm::min(ds, t1 - start(k)); }
  PENUMBRA_HD float position(int k) const { return start(k) + offset * length(k); }
  // First segment whose sample lies at or after t.
  PENUMBRA_HD int first_at_or_after(float t) const {
    int k = int(glm::ceil((t - t0) / ds - offset));
    k = k < 0 ? 0 : (k > count ? count : k);
    while (k > 0 && position(k - 1) >= t) --k;
    while (k < count && position(k) < t) ++k;
    return k;
  }
};

// Calls visit(t_begin, t_end, majorant) for every macrocell that the ray
// crosses within [t0, t1] and whose majorant is positive, front to back (3D
// DDA, Amanatides & Woo 1987). Stops early when visit returns false.
template <class Visit>
PENUMBRA_HD void traverse_macrocells(const RenderView& v, const Ray& ray, float t0, float t1, Visit&& visit) {
  const float size = float(v.macrocells.cell_size);
  const ivec3 dims = v.macrocells.dims;
  const vec3 o = v.volume.index_from_world(ray.origin);
  const vec3 d = ray.direction / v.volume.spacing;
  ivec3 cell = glm::clamp(ivec3(glm::floor((o + t0 * d) / size)), ivec3(0), dims - 1);
  ivec3 step(0);
  vec3 t_next(kInfinity);
  vec3 t_delta(kInfinity);
  for (int a = 0; a < 3; ++a) {
    if (d[a] > 0.0f) {
      step[a] = 1;
      t_next[a] = (float(cell[a] + 1) * size - o[a]) / d[a];
      t_delta[a] = size / d[a];
    } else if (d[a] < 0.0f) {
      step[a] = -1;
      t_next[a] = (float(cell[a]) * size - o[a]) / d[a];
      t_delta[a] = -size / d[a];
    }
  }
  float t = t0;
  while (t < t1) {
    const int axis = t_next.x < t_next.y ? (t_next.x < t_next.z ? 0 : 2) : (t_next.y < t_next.z ? 1 : 2);
    const float t_exit = glm::min(t_next[axis], t1);
    const float majorant = v.majorants[v.macrocells.index(cell)];
    if (majorant > 0.0f && t_exit > t) {
      if (!visit(t, t_exit, majorant)) return;
    }
    t = glm::max(t, t_exit);
    cell[axis] += step[axis];
    if (cell[axis] < 0 || cell[axis] >= dims[axis]) return;
    t_next[axis] += t_delta[axis];
  }
}

// Calls sample(k, t) for every segment of `grid` whose sample lies in a
// non-empty macrocell, front to back; stops when sample returns false.
template <class Sample>
PENUMBRA_HD void for_each_sample(const RenderView& v, const Ray& ray, const SampleGrid& grid, Sample&& sample) {
  traverse_macrocells(v, ray, grid.t0, grid.t1, [&](float a, float b, float) {
    const bool last_cell = b >= grid.t1;
    for (int k = grid.first_at_or_after(a); k < grid.count; ++k) {
      const float t = grid.position(k);
      if (!last_cell && t >= b) break;
      if (!sample(k, t)) return false;
    }
    return true;
  });
}

// The part of a ray inside the volume box and the clip planes, within [t_min, t_max].
PENUMBRA_HD inline Interval volume_interval(const RenderView& v, const Ray& ray, float t_min, float t_max) {
  return clip_interval(ray, v.clip_planes, v.clip_plane_count, intersect_box(ray, v.box, t_min, t_max));
}

// Optical depth beyond which transmittance counts as zero (e^-11.5 ~ 1e-5).
inline constexpr float kMaxOpticalDepth = 11.5f;

// Transmittance exp(-integral sigma_t) from ray.origin along ray.direction up
// to t_max (the volume boundary or a point light), with sigma_t scaled by
// density_scale. Respects clip planes; skips empty macrocells.
PENUMBRA_HD inline float march_transmittance(const RenderView& v, const Ray& ray, float t_max, float density_scale,
                                             RayStats& stats) {
  const SampleGrid grid(volume_interval(v, ray, 0.0f, t_max), v.step, 0.5f);
  if (grid.count == 0 || density_scale <= 0.0f) return 1.0f;
  const vec3 o = v.volume.index_from_world(ray.origin);
  const vec3 d = ray.direction / v.volume.spacing;
  float depth = 0.0f;
  for_each_sample(v, ray, grid, [&](int k, float t) {
    ++stats.samples;
    depth += v.tf.lookup(v.volume.sample_index(o + t * d)).a * grid.length(k) * density_scale;
    return depth < kMaxOpticalDepth;
  });
  return depth < kMaxOpticalDepth ? glm::exp(-depth) : 0.0f;
}

// Nearest opaque plane along the ray in (0, t_max); returns its index or -1.
PENUMBRA_HD inline int nearest_plane(const RenderView& v, const Ray& ray, float t_max, float& t_hit) {
  int hit = -1;
  t_hit = t_max;
  for (int i = 0; i < v.plane_count; ++i) {
    const float t = intersect_plane(ray, v.planes[i], 0.0f, t_hit);
    if (t < t_hit) {
      t_hit = t;
      hit = i;
    }
  }
  return hit;
}

// Front-to-back compositing of one viewing ray. Returns linear rgb and the
// accumulated opacity (1 where an opaque plane was reached).
template <class Lighting>
PENUMBRA_HD vec4 march_ray(const RenderView& v, const Ray& ray, float offset, const Lighting& lighting,
                           RayStats& stats) {
  float t_plane = kInfinity;
  const int plane = nearest_plane(v, ray, kInfinity, t_plane);
  const SampleGrid grid(volume_interval(v, ray, 0.0f, t_plane), v.step, offset);
  const vec3 o = v.volume.index_from_world(ray.origin);
  const vec3 d = ray.direction / v.volume.spacing;
  vec3 color(0.0f);
  float transmittance = 1.0f;
  const float min_transmittance = 1.0f - v.ert_threshold;
  bool terminated = false;
  if (grid.count > 0) {
    for_each_sample(v, ray, grid, [&](int k, float t) {
      ++stats.samples;
      const vec3 p = o + t * d;
      const float value = v.volume.sample_index(p);
      const vec4 c = v.tf.lookup(value);
      if (c.a <= 0.0f) return true;
      const float alpha = 1.0f - glm::exp(-c.a * grid.length(k));
      const SamplePoint s{ray.at(t), p, value, vec3(c), c.a, ray.direction};
      color += (transmittance * alpha) * lighting.sample(s);
      transmittance *= 1.0f - alpha;
      terminated = transmittance <= min_transmittance;
      return !terminated;
    });
  }
  if (terminated) return vec4(color, 1.0f - transmittance);
  if (plane >= 0) {
    color += transmittance * lighting.plane(PlaneHit{ray.at(t_plane), plane, ray.direction});
    return vec4(color, 1.0f);
  }
  return vec4(color + transmittance * v.background, 1.0f - transmittance);
}

}  // namespace penumbra

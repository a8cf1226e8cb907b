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
//
// Kernels take a Sampler (VolumeSampler<T>, see volume_sampler.h) so the
// per-sample code is specialised for the voxel type.
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

// The macrocell walk of one ray: a 3D DDA (Amanatides & Woo 1987) that also
// jumps over cubes of empty macrocells using the empty-space distance.
class MacrocellWalk {
 public:
  PENUMBRA_HD MacrocellWalk(const RenderView& v, const Ray& ray, float t)
      : v_(v), size_(float(v.macrocells.cell_size)), origin_(v.volume.index_from_world(ray.origin)),
        dir_(ray.direction / v.volume.spacing) {
    for (int a = 0; a < 3; ++a) inv_dir_[a] = dir_[a] != 0.0f ? 1.0f / dir_[a] : 0.0f;
    restart(t);
  }

  PENUMBRA_HD float t() const { return t_; }
  PENUMBRA_HD float majorant() const { return v_.majorants[v_.macrocells.index(cell_)]; }
  PENUMBRA_HD float cell_exit() const { return glm::min(t_next_.x, glm::min(t_next_.y, t_next_.z)); }

  // Moves to the next macrocell along the ray; false when the ray leaves the grid.
  PENUMBRA_HD bool step() {
    const int axis = t_next_.x < t_next_.y ? (t_next_.x < t_next_.z ? 0 : 2) : (t_next_.y < t_next_.z ? 1 : 2);
    t_ = glm::max(t_, t_next_[axis]);
    cell_[axis] += step_[axis];
    if (cell_[axis] < 0 || cell_[axis] >= v_.macrocells.dims[axis]) return false;
    t_next_[axis] += t_delta_[axis];
    return true;
  }

  // In an empty cell: moves past the cube of cells that are all empty around
  // it (or one cell when that cube is the cell itself). False when the ray
  // leaves the grid.
  PENUMBRA_HD bool skip_empty() {
    const int radius = int(v_.empty_distance[v_.macrocells.index(cell_)]) - 1;
    if (radius < 1) return step();
    float t_exit = kInfinity;
    for (int a = 0; a < 3; ++a) {
      if (dir_[a] == 0.0f) continue;
      const float bound = dir_[a] > 0.0f ? float(cell_[a] + radius + 1) * size_ : float(cell_[a] - radius) * size_;
      t_exit = glm::min(t_exit, (bound - origin_[a]) * inv_dir_[a]);
    }
    if (!(t_exit > cell_exit())) return step();
    restart(t_exit);
    return inside_;
  }

 private:
  PENUMBRA_HD void restart(float t) {
    t_ = t;
    const vec3 p = (origin_ + t * dir_) / size_;
    const ivec3 dims = v_.macrocells.dims;
    inside_ = true;
    for (int a = 0; a < 3; ++a) {
      float c = glm::floor(p[a]);
      // On a cell boundary, belong to the cell the ray moves into.
      if (dir_[a] < 0.0f && c == p[a]) c -= 1.0f;
      cell_[a] = int(c);
      if (cell_[a] < 0 || cell_[a] >= dims[a]) {
        // Rounding at the grid border when entering: clamp; leaving: stop.
        const bool entering = (cell_[a] < 0) == (dir_[a] > 0.0f);
        if (!entering && dir_[a] != 0.0f) inside_ = false;
        cell_[a] = glm::clamp(cell_[a], 0, dims[a] - 1);
      }
      if (dir_[a] > 0.0f) {
        step_[a] = 1;
        t_next_[a] = (float(cell_[a] + 1) * size_ - origin_[a]) * inv_dir_[a];
        t_delta_[a] = size_ * inv_dir_[a];
      } else if (dir_[a] < 0.0f) {
        step_[a] = -1;
        t_next_[a] = (float(cell_[a]) * size_ - origin_[a]) * inv_dir_[a];
        t_delta_[a] = -size_ * inv_dir_[a];
      } else {
        step_[a] = 0;
        t_next_[a] = kInfinity;
        t_delta_[a] = kInfinity;
      }
    }
  }

  const RenderView& v_;
  float size_;
  vec3 origin_;
  vec3 dir_;
  vec3 inv_dir_{0.0f};
  float t_ = 0.0f;
  bool inside_ = true;
  ivec3 cell_{0};
  ivec3 step_{0};
  vec3 t_next_{kInfinity};
  vec3 t_delta_{kInfinity};
};

// The runs of consecutive non-empty macrocells that a ray crosses within
// [t0, t1], front to back, with empty space skipped:
//   OccupiedRuns runs(view, ray, t0, t1);
//   for (float a, b; runs.next(a, b);) { ... }
class OccupiedRuns {
 public:
  PENUMBRA_HD OccupiedRuns(const RenderView& v, const Ray& ray, float t0, float t1) : walk_(v, ray, t0), t1_(t1) {}

  PENUMBRA_HD PENUMBRA_FORCE_INLINE bool next(float& a, float& b) {
    while (alive_ && walk_.t() < t1_) {
      if (walk_.majorant() > 0.0f) {
        if (run_start_ < 0.0f) run_start_ = walk_.t();
        alive_ = walk_.step();
      } else {
        const bool ends_run = run_start_ >= 0.0f;
        if (ends_run) {
          a = run_start_;
          b = glm::min(walk_.t(), t1_);
          run_start_ = -1.0f;
        }
        alive_ = walk_.skip_empty();
        if (ends_run) return true;
      }
    }
    if (run_start_ >= 0.0f && run_start_ < t1_) {
      a = run_start_;
      b = glm::min(walk_.t(), t1_);
      run_start_ = -1.0f;
      return true;
    }
    return false;
  }

 private:
  MacrocellWalk walk_;
  float t1_;
  float run_start_ = -1.0f;  // < 0: not inside a run
  bool alive_ = true;
};

// Calls visit(t_begin, t_end, majorant) for every macrocell with a positive
// majorant that the ray crosses within [t0, t1], front to back (the path
// tracer's piecewise-constant majorant). Stops when visit returns false.
template <class Visit>
PENUMBRA_HD void for_each_occupied_cell(const RenderView& v, const Ray& ray, float t0, float t1, Visit&& visit) {
  MacrocellWalk walk(v, ray, t0);
  while (walk.t() < t1) {
    const float m = walk.majorant();
    if (m > 0.0f) {
      const float end = glm::min(walk.cell_exit(), t1);
      if (end > walk.t() && !visit(walk.t(), end, m)) return;
      if (!walk.step()) return;
    } else if (!walk.skip_empty()) {
      return;
    }
  }
}

// The samples of `grid` that lie in non-empty macrocells, front to back:
//   SampleCursor cursor(view, ray, grid);
//   for (int k; float t; cursor.next(k, t)) { ... segment k, at ray parameter t ... }
// A plain loop rather than a callback, so the caller's accumulators stay in
// registers.
class SampleCursor {
 public:
  PENUMBRA_HD SampleCursor(const RenderView& v, const Ray& ray, const SampleGrid& grid)
      : runs_(v, ray, grid.t0, grid.t1), grid_(grid), k_(grid.count) {}

  PENUMBRA_HD PENUMBRA_FORCE_INLINE bool next(int& k, float& t) {
    for (;;) {
      if (k_ < grid_.count) {
        const float tk = grid_.position(k_);
        if (last_run_ || tk < run_end_) {
          k = k_++;
          t = tk;
          return true;
        }
      } else if (started_) {
        return false;  // every segment has been visited
      }
      float a = 0.0f, b = 0.0f;
      if (!runs_.next(a, b)) return false;
      started_ = true;
      run_end_ = b;
      last_run_ = b >= grid_.t1;
      k_ = grid_.first_at_or_after(a);
    }
  }

 private:
  OccupiedRuns runs_;
  const SampleGrid& grid_;
  int k_;
  float run_end_ = 0.0f;
  bool last_run_ = false;
  bool started_ = false;
};

// The part of a ray inside the volume box and the clip planes, within [t_min, t_max].
PENUMBRA_HD inline Interval volume_interval(const RenderView& v, const Ray& ray, float t_min, float t_max) {
  return clip_interval(ray, v.clip_planes, v.clip_plane_count, intersect_box(ray, v.box, t_min, t_max));
}

// Optical depth beyond which transmittance counts as zero (e^-11.5 ~ 1e-5).
inline constexpr float kMaxOpticalDepth = 11.5f;

// Transmittance exp(-integral sigma_t) from ray.origin along ray.direction up
// to t_max (the volume boundary or a point light), with sigma_t scaled by
// density_scale. Respects clip planes; skips empty macrocells.
template <class Sampler>
PENUMBRA_HD float march_transmittance(const RenderView& v, const Sampler& sampler, const Ray& ray, float t_max,
                                      float density_scale, RayStats& stats) {
  const SampleGrid grid(volume_interval(v, ray, 0.0f, t_max), v.step, 0.5f);
  if (grid.count == 0 || density_scale <= 0.0f) return 1.0f;
  const vec3 o = v.volume.index_from_world(ray.origin);
  const vec3 d = ray.direction / v.volume.spacing;
  const TransferFunctionView tf = v.tf;
  float depth = 0.0f;
  std::uint64_t samples = 0;
  SampleCursor cursor(v, ray, grid);
  int k;
  float t;
  while (cursor.next(k, t)) {
    ++samples;
    const float value = sampler(o + t * d);
    depth += (Sampler::kAlwaysFinite ? tf.lookup_finite(value) : tf.lookup(value)).a * grid.length(k);
    if (depth * density_scale >= kMaxOpticalDepth) break;
  }
  stats.samples += samples;
  depth *= density_scale;
  return depth < kMaxOpticalDepth ? exp_nonpositive(-depth) : 0.0f;
}

// The same, dispatching on the voxel type (one switch per ray).
PENUMBRA_HD inline float march_transmittance(const RenderView& v, const Ray& ray, float t_max, float density_scale,
                                             RayStats& stats) {
  return with_sampler(v.volume, [&](const auto& sampler) {
    return march_transmittance(v, sampler, ray, t_max, density_scale, stats);
  });
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
template <class Sampler, class Lighting>
PENUMBRA_HD vec4 march_ray(const RenderView& v, const Sampler& sampler, const Ray& ray, float offset,
                           const Lighting& lighting, RayStats& stats) {
  float t_plane = kInfinity;
  const int plane = nearest_plane(v, ray, kInfinity, t_plane);
  const SampleGrid grid(volume_interval(v, ray, 0.0f, t_plane), v.step, offset);
  const vec3 o = v.volume.index_from_world(ray.origin);
  const vec3 d = ray.direction / v.volume.spacing;
  const TransferFunctionView tf = v.tf;
  const float min_transmittance = 1.0f - v.ert_threshold;
  vec3 color(0.0f);
  float transmittance = 1.0f;
  std::uint64_t samples = 0;
  SampleCursor cursor(v, ray, grid);
  int k;
  float t;
  while (cursor.next(k, t)) {
    ++samples;
    const vec3 p = o + t * d;
    const float value = sampler(p);
    const vec4 c = Sampler::kAlwaysFinite ? tf.lookup_finite(value) : tf.lookup(value);
    if (c.a <= 0.0f) continue;
    const float alpha = 1.0f - exp_nonpositive(-c.a * grid.length(k));
    const SamplePoint s{ray.at(t), p, value, vec3(c), c.a, ray.direction};
    color += (transmittance * alpha) * lighting.sample(s);
    transmittance *= 1.0f - alpha;
    if (transmittance <= min_transmittance) {
      stats.samples += samples;
      return vec4(color, 1.0f - transmittance);  // early ray termination
    }
  }
  stats.samples += samples;
  if (plane >= 0) {
    color += transmittance * lighting.plane(PlaneHit{ray.at(t_plane), plane, ray.direction});
    return vec4(color, 1.0f);
  }
  return vec4(color + transmittance * v.background, 1.0f - transmittance);
}

}  // namespace penumbra

#pragma once
// Where a ray takes its samples: the sample grid of its interval, the walk
// over the macrocell grid that skips empty space, and the cursor that visits
// the samples lying in occupied macrocells, front to back. The walk and the
// cursor are written once over a lane type (base/lanes.h): LaneCursor<L>
// walks L::kWidth rays at once, each lane over its own cells, and its
// one-lane instance is the scalar SampleCursor.
//
// Sampling convention: the ray's interval [t0, t1] is cut into segments of the
// step ds (the last one shorter); segment k is represented by one sample at
// offset * length inside it (offset 0.5 = midpoint, or a per-pixel random
// value with jitter). Segment lengths add up to t1 - t0 exactly, so a
// homogeneous medium integrates to exp(-sigma_t (t1 - t0)) at any step.
//
// A sample is taken when it lies in a run of occupied macrocells (majorant
// > 0) that the walk crosses: at or after the time the walk enters the run's
// first cell and before it enters the next empty one (the last run of a ray
// takes every sample up to t1).
#include "penumbra/base/lanes.h"
#include "penumbra/base/ray.h"
#include "penumbra/render/render_view.h"

#include <cstdint>

namespace penumbra {

struct SampleGrid {
  float t0 = 0.0f;
  float t1 = 0.0f;
  float ds = 1.0f;
  float offset = 0.5f;
  int count = 0;

  SampleGrid() = default;
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

// The macrocell walk of one ray per lane: a 3D DDA (Amanatides & Woo 1987)
// that also jumps over cubes of empty macrocells using the empty-space
// distance. Every operation acts on the lanes of a mask and leaves the
// others as they are. Positions are in index space; t is the ray parameter.
template <class L> struct LaneWalk {
  using F = typename L::Float;
  using I = typename L::Int;
  using M = typename L::Mask;
  using V = typename L::Vec3;

  const RenderView* view = nullptr;
  float size = 1.0f;  // macrocell side in voxels
  V origin, dir, inv_dir;
  F t;       // where the walk entered its current cell
  M inside;  // false once a jump left the grid
  I cell[3], step[3];
  F t_next[3], t_delta[3];
  // What depends only on the direction, set by start() and read by
  // restart() and skip_empty() (recomputed there, it was hoisted into the
  // packet loop's every step and spilled: issue 14).
  M forward[3], backward[3];

  LaneWalk() = default;
  PENUMBRA_HD explicit LaneWalk(const RenderView& v)
      : view(&v), size(float(v.macrocells.cell_size)), origin(0.0f), dir(0.0f), inv_dir(0.0f), t(0.0f),
        inside(true) {
    for (int a = 0; a < 3; ++a) {
      cell[a] = step[a] = I(0);
      t_next[a] = t_delta[a] = F(kInfinity);
      forward[a] = backward[a] = M(false);
    }
  }

  // Lanes of `lanes` start walking the ray (index-space origin o, direction
  // d) at t0.
  PENUMBRA_HD PENUMBRA_FORCE_INLINE void start(typename L::Mask lanes, const V& o, const V& d, F t0) {
    origin = select(lanes, o, origin);
    dir = select(lanes, d, dir);
    for (int a = 0; a < 3; ++a) {
      const auto moving = d[a] != 0.0f;
      const F inv = select(moving, 1.0f / select(moving, d[a], F(1.0f)), F(0.0f));
      inv_dir[a] = select(lanes, inv, inv_dir[a]);
      const M ahead = d[a] > 0.0f, back = d[a] < 0.0f;
      forward[a] = select(lanes, ahead, forward[a]);
      backward[a] = select(lanes, back, backward[a]);
      step[a] = select(lanes, select(ahead, I(1), select(back, I(-1), I(0))), step[a]);
      t_delta[a] = select(lanes, select(ahead, size * inv, select(back, -size * inv, F(kInfinity))), t_delta[a]);
    }
    restart(lanes, t0);
  }

  PENUMBRA_HD PENUMBRA_FORCE_INLINE F cell_exit() const { return min(t_next[0], min(t_next[1], t_next[2])); }
  PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Index cell_index() const {
    using X = typename L::Index;
    const ivec3 dims = view->macrocells.dims;
    return X(cell[0]) + X(dims.x) * (X(cell[1]) + X(dims.y) * X(cell[2]));
  }
  PENUMBRA_HD PENUMBRA_FORCE_INLINE F majorant() const { return gather(view->majorants, cell_index()); }
  // The same read only for `lanes` (the others may stand outside the grid).
  PENUMBRA_HD PENUMBRA_FORCE_INLINE F majorant(M lanes) const {
    return gather(view->majorants, select(lanes, cell_index(), typename L::Index(0)));
  }

  // Moves the lanes to their next macrocell; the lanes that are still in the grid.
  PENUMBRA_HD PENUMBRA_FORCE_INLINE M advance(M lanes) {
    const M x_first = t_next[0] < t_next[1];
    const M x_axis = x_first & (t_next[0] < t_next[2]);
    const M y_axis = (!x_first) & (t_next[1] < t_next[2]);
    const M z_axis = (!x_axis) & (!y_axis);
    const M axis_of[3] = {x_axis, y_axis, z_axis};
    M left(false);
    for (int a = 0; a < 3; ++a) {
      const M m = lanes & axis_of[a];
      if (none(m)) continue;
      t = select(m, max(t, t_next[a]), t);
      cell[a] = select(m, cell[a] + step[a], cell[a]);
      const M out = m & ((cell[a] < I(0)) | (cell[a] >= I(view->macrocells.dims[a])));
      left = left | out;
      t_next[a] = select(m & !out, t_next[a] + t_delta[a], t_next[a]);
    }
    return lanes & !left;
  }

  // In an empty cell: moves past the cube of cells that are all empty around
  // it (or one cell when that cube is the cell itself). The lanes that are
  // still in the grid.
  PENUMBRA_HD PENUMBRA_FORCE_INLINE M skip_empty(M lanes) {
    const auto& grid = view->macrocells;
    const std::int64_t cells = std::int64_t(grid.dims.x) * grid.dims.y * grid.dims.z;
    const I radius = to_int(load_voxel(view->empty_distance, select(lanes, cell_index(), typename L::Index(0)),
                                       cells)) - I(1);
    F t_exit(kInfinity);
    for (int a = 0; a < 3; ++a) {
      const F bound = select(forward[a], to_float(cell[a] + radius + I(1)) * size, to_float(cell[a] - radius) * size);
      t_exit = select(forward[a] | backward[a], min(t_exit, (bound - origin[a]) * inv_dir[a]), t_exit);
    }
    const M jump = lanes & !(radius < I(1)) & (t_exit > cell_exit());
    const M stepping = lanes & !jump;
    M in_grid(false);
    if (any(stepping)) in_grid = advance(stepping);
    if (any(jump)) {
      restart(jump, t_exit);
      in_grid = in_grid | (jump & inside);
    }
    return in_grid;
  }

  // The lanes enter the cell that holds the ray at t.
  PENUMBRA_HD PENUMBRA_FORCE_INLINE void restart(M lanes, F at) {
    t = select(lanes, at, t);
    const V p = (origin + at * dir) / size;
    const ivec3 dims = view->macrocells.dims;
    inside = inside | lanes;
    for (int a = 0; a < 3; ++a) {
      F c = floor(p[a]);
      // On a cell boundary, belong to the cell the ray moves into.
      c = select(backward[a] & (c == p[a]), c - 1.0f, c);
      I index = to_int(c);
      const M outside = (index < I(0)) | (index >= I(dims[a]));
      // Rounding at the grid border when entering: clamp; leaving: stop.
      const M entering = (index < I(0)) == forward[a];
      inside = select(lanes & outside & !entering & (forward[a] | backward[a]), M(false), inside);
      index = max(I(0), min(index, I(dims[a] - 1)));
      cell[a] = select(lanes, index, cell[a]);
      const F plane = to_float(select(forward[a], index + I(1), index)) * size;
      t_next[a] = select(lanes, select(forward[a] | backward[a], (plane - origin[a]) * inv_dir[a], F(kInfinity)),
                         t_next[a]);
    }
  }
};

// The walk of one ray, as OccupiedRuns and the path tracer's majorant walk
// use it: LaneWalk's one-lane instance.
class MacrocellWalk {
 public:
  MacrocellWalk() = default;
  PENUMBRA_HD PENUMBRA_FORCE_INLINE MacrocellWalk(const RenderView& v, const Ray& ray, float t) : walk_(v) {
    walk_.start(true, v.volume.index_from_world(ray.origin), ray.direction / v.volume.spacing, t);
  }
  PENUMBRA_HD float t() const { return walk_.t; }
  PENUMBRA_HD float majorant() const { return walk_.majorant(); }
  PENUMBRA_HD float cell_exit() const { return walk_.cell_exit(); }
  // Moves to the next macrocell along the ray; false when the ray leaves the grid.
  PENUMBRA_HD PENUMBRA_FORCE_INLINE bool step() { return walk_.advance(true); }
  // In an empty cell: moves past the empty cells around it; false when the
  // ray leaves the grid.
  PENUMBRA_HD PENUMBRA_FORCE_INLINE bool skip_empty() { return walk_.skip_empty(true); }

 private:
  LaneWalk<ScalarLanes> walk_;
};

// The runs of consecutive non-empty macrocells that a ray crosses within
// [t0, t1], front to back, with empty space skipped:
//   OccupiedRuns runs(view, ray, t0, t1);
//   for (float a, b; runs.next(a, b);) { ... }
class OccupiedRuns {
 public:
  OccupiedRuns() = default;
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
  float t1_ = 0.0f;
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

// The samples of L::kWidth rays that lie in occupied macrocells, front to
// back, lane i on its own ray. next() gives every lane that has a sample
// left its next one (`has`), in lockstep; a lane moves its walk only when its
// sample passes the exit of its current cell, so the common step is a
// handful of packet operations. A lane's ray ends when its samples run out
// or stop() retires it (early ray termination); take_finished() reports
// those lanes so the caller can start new rays on them (start()), which keeps
// the lanes busy while rays of different lengths come and go.
template <class L> class LaneCursor {
  using F = typename L::Float;
  using I = typename L::Int;
  using M = typename L::Mask;
  using V = typename L::Vec3;
  static constexpr int W = L::kWidth;

 public:
  // No lane has a ray yet; every ray will sample with step `ds`.
  PENUMBRA_HD LaneCursor(const RenderView& v, float ds) : walk_(v), ds_(ds) {
    for (int i = 0; i < W; ++i) {
      t0_[i] = t1_[i] = offset_[i] = 0.0f;
      count_[i] = 0;
      for (int c = 0; c < 6; ++c) ray_[c][i] = 0.0f;
    }
    t0_v_ = t1_v_ = offset_v_ = F(0.0f);
    k_v_ = count_v_ = I(0);
    alive_v_ = M(false);
  }
  // Lanes on in `lanes` start on rays[i] with sample grid grids[i].
  PENUMBRA_HD LaneCursor(const RenderView& v, const Ray* rays, const SampleGrid* grids, M lanes)
      : LaneCursor(v, grids[0].ds) {
    begin_starts();
    const std::uint32_t on = L::bits(lanes);
    for (int i = 0; i < W; ++i) {
      if ((on >> i) & 1u) start(i, rays[i], grids[i]);
    }
    end_starts();
  }

  // Starts lanes on new rays: begin_starts(), start(lane, ...) for each, end_starts().
  PENUMBRA_HD void begin_starts() { started_ = 0; }
  PENUMBRA_HD void start(int i, const Ray& ray, const SampleGrid& grid) {
    const VolumeView& volume = walk_.view->volume;
    const vec3 o = volume.index_from_world(ray.origin), d = ray.direction / volume.spacing;
    for (int a = 0; a < 3; ++a) {
      ray_[a][i] = o[a];
      ray_[3 + a][i] = d[a];
    }
    t0_[i] = grid.t0;
    t1_[i] = grid.t1;
    offset_[i] = grid.offset;
    count_[i] = grid.count;
    started_ |= 1u << i;
  }
  PENUMBRA_HD void end_starts() {
    if (started_ == 0) return;
    t0_v_ = L::load(t0_);
    t1_v_ = L::load(t1_);
    offset_v_ = L::load(offset_);
    count_v_ = L::load(count_);
    const M started = L::from_bits(started_);
    k_v_ = select(started, I(0), k_v_);
    const M sampled = started & (I(0) < count_v_);
    alive_v_ = select(started, sampled, alive_v_);
    finished_ |= L::bits(started & !sampled);  // nothing to sample: done at once
    if (none(sampled)) return;
    walk_.start(sampled, V(L::load(ray_[0]), L::load(ray_[1]), L::load(ray_[2])),
                V(L::load(ray_[3]), L::load(ray_[4]), L::load(ray_[5])), t0_v_);
    enter_runs(sampled);
  }

  // The ray parameter t and segment length of each lane's next sample, on in
  // `has`; false when no lane has a sample left.
  PENUMBRA_HD PENUMBRA_FORCE_INLINE bool next(F& t, F& length, M& has) {
    for (;;) {
      t = position(k_v_, length);
      const F exit = walk_.cell_exit();
      has = alive_v_ & (k_v_ < count_v_) & ((t < exit) | (exit >= t1_v_));
      const M behind = alive_v_ & !has;
      if (none(behind)) break;
      move_on(behind);
    }
    sample_k_ = k_v_;
    k_v_ = select(has, k_v_ + I(1), k_v_);
    return any(has);
  }
  // The segment index of the sample next() gave each lane.
  PENUMBRA_HD I sample_index() const { return sample_k_; }

  // Ends the rays of `lanes` now.
  PENUMBRA_HD void stop(M lanes) { retire(alive_v_ & lanes); }

  // The lanes whose ray ended since the last call.
  PENUMBRA_HD std::uint32_t take_finished() {
    const std::uint32_t f = finished_;
    finished_ = 0;
    return f;
  }

 private:
  PENUMBRA_HD PENUMBRA_FORCE_INLINE F position(I k, F& length) const {
    const F begin = t0_v_ + to_float(k) * ds_;
    length = min(F(ds_), t1_v_ - begin);
    return begin + offset_v_ * length;
  }

  PENUMBRA_HD PENUMBRA_FORCE_INLINE void retire(M lanes) {
    finished_ |= L::bits(lanes);
    alive_v_ = alive_v_ & !lanes;
  }

  // Lanes whose next sample does not lie in their current cell: out of
  // samples, or on to the next cell, and past the empty cells after it.
  // Out of line: the walk's state stays in memory, not in the registers of
  // the loop that calls next() (docs/PERFORMANCE.md, issue 14).
  PENUMBRA_HD PENUMBRA_COLD_PATH void move_on(M lanes) {
    const M spent = lanes & !(k_v_ < count_v_);
    retire(spent);
    lanes = lanes & !spent;
    if (none(lanes)) return;
    const M in_grid = walk_.advance(lanes);
    retire(lanes & !in_grid);  // what is left lies beyond the run that ended with the grid
    const M empty = in_grid & !(walk_.majorant(in_grid) > 0.0f);
    if (any(empty)) enter_runs(empty);
  }

  // Lanes whose walk stands in a cell that may be empty: walk on to the next
  // occupied cell (before t1) and begin the run there at the first sample at
  // or after the walk's time; lanes that find none are done.
  PENUMBRA_HD PENUMBRA_COLD_PATH void enter_runs(M lanes) {
    while (any(lanes)) {
      const M beyond = lanes & !(walk_.t < t1_v_);
      retire(beyond);
      lanes = lanes & !beyond;
      const M occupied = lanes & (walk_.majorant(lanes) > 0.0f);
      if (any(occupied)) {
        k_v_ = select(occupied, first_at_or_after(walk_.t), k_v_);
        lanes = lanes & !occupied;
      }
      if (none(lanes)) return;
      const M in_grid = walk_.skip_empty(lanes);
      retire(lanes & !in_grid);
      lanes = lanes & in_grid;
    }
  }

  // The first segment whose sample lies at or after t (SampleGrid::first_at_or_after).
  PENUMBRA_HD PENUMBRA_FORCE_INLINE I first_at_or_after(F t) const {
    F length;
    I k = to_int(-floor(-((t - t0_v_) / ds_ - offset_v_)));  // ceil
    k = max(I(0), min(k, count_v_));
    for (M down = (k > I(0)) & (position(k - I(1), length) >= t); any(down);
         down = (k > I(0)) & (position(k - I(1), length) >= t)) {
      k = select(down, k - I(1), k);
    }
    for (M up = (k < count_v_) & (position(k, length) < t); any(up); up = (k < count_v_) & (position(k, length) < t)) {
      k = select(up, k + I(1), k);
    }
    return k;
  }

  LaneWalk<L> walk_;
  float ds_;
  F t0_v_, t1_v_, offset_v_;
  I k_v_, count_v_, sample_k_;
  M alive_v_;
  // Per lane, for starts.
  float ray_[6][W];  // index-space origin and direction
  float t0_[W], t1_[W], offset_[W];
  std::int32_t count_[W];
  std::uint32_t started_ = 0, finished_ = 0;
};

// The samples of `grid` that lie in non-empty macrocells, front to back:
//   SampleCursor cursor(view, ray, grid);
//   for (int k; float t; cursor.next(k, t)) { ... segment k, at ray parameter t ... }
// A plain loop rather than a callback, so the caller's accumulators stay in
// registers. LaneCursor's one-lane instance.
class SampleCursor {
 public:
  PENUMBRA_HD SampleCursor(const RenderView& v, const Ray& ray, const SampleGrid& grid)
      : cursor_(v, &ray, &grid, true) {}

  PENUMBRA_HD PENUMBRA_FORCE_INLINE bool next(int& k, float& t) {
    float length;
    bool has;
    if (!cursor_.next(t, length, has)) return false;
    k = cursor_.sample_index();
    return true;
  }

 private:
  LaneCursor<ScalarLanes> cursor_;
};

}  // namespace penumbra

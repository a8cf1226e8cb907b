#pragma once
// The marching loop every technique shares (DESIGN.md 1): clip the ray to the
// volume box, the clip planes and the nearest opaque plane, walk the macrocell
// grid so empty space costs no samples (sample_cursor.h), and composite front
// to back with opacity correction alpha = 1 - exp(-sigma_t * length) and early
// ray termination. A technique supplies only how a sample is lit (a Lighting
// type with sample() and plane(), see lighting.h).
//
// The loop is written once over a lane type L (base/lanes.h): march_rays<L>
// marches L::kWidth rays in lockstep, each lane with its own interval,
// macrocell walk and termination. march_ray() is its one-lane instance (the
// scalar CPU path and CUDA); the CPU backend's packet path instantiates it
// with SimdLanes (backends/cpu).
//
// Kernels take a Sampler (VolumeSampler<T> or AnyVoxelSampler, see
// volume_sampler.h) with sample<L>(index position) and all_finite().
#include "penumbra/base/lanes.h"
#include "penumbra/base/ray.h"
#include "penumbra/render/render_view.h"
#include "penumbra/render/sample_cursor.h"
#include "penumbra/volume/volume_sampler.h"

#include <cstdint>

namespace penumbra {

struct RayStats {
  std::uint64_t samples = 0;  // volume samples taken (trilinear lookups)
  std::uint64_t steps = 0;    // packet steps of viewing rays (samples / (steps * lanes): lane utilisation)
};

// One volume sample as Lighting::sample sees it, for one ray or a packet.
template <class L> struct SamplePointL {
  typename L::Vec3 world;      // world position
  typename L::Vec3 index;      // index-space position
  typename L::Float value;     // interpolated scalar
  typename L::Vec3 color;      // TF colour
  typename L::Float sigma_t;   // extinction per world unit
  typename L::Vec3 ray_dir;    // unit direction of the viewing ray
  // The volume sample's grid cell, where the marching loop has it (normals
  // interpolate in the same cell), or null.
  const GridCell<L>* cell = nullptr;
};
using SamplePoint = SamplePointL<ScalarLanes>;

struct PlaneHit {
  vec3 position;
  int plane;  // index into RenderView::planes
  vec3 ray_dir;
};

// W scalar vectors as one vector of lanes.
template <class L> PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Vec3 pack_lanes(const vec3* values) {
  float x[L::kWidth], y[L::kWidth], z[L::kWidth];
  for (int i = 0; i < L::kWidth; ++i) {
    x[i] = values[i].x;
    y[i] = values[i].y;
    z[i] = values[i].z;
  }
  return typename L::Vec3(L::load(x), L::load(y), L::load(z));
}

// One vector of lanes as W scalar vectors.
template <class L> PENUMBRA_HD PENUMBRA_FORCE_INLINE void unpack_lanes(const typename L::Vec3& lanes, vec3* values) {
  float x[L::kWidth], y[L::kWidth], z[L::kWidth];
  L::store(lanes.x, x);
  L::store(lanes.y, y);
  L::store(lanes.z, z);
  for (int i = 0; i < L::kWidth; ++i) values[i] = vec3(x[i], y[i], z[i]);
}

// Lighting::sample for one ray or a packet: the Lighting's lane form when it
// has one (sample<L>(s, active)), else its scalar sample(s) on one lane.
template <class L, class Lighting>
PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Vec3 light_sample(const Lighting& lighting, const SamplePointL<L>& s,
                                                                typename L::Mask active) {
  if constexpr (requires { lighting.template sample<L>(s, active); }) {
    return lighting.template sample<L>(s, active);
  } else {
    static_assert(L::kWidth == 1, "a Lighting with a packet path needs template <class L> sample(SamplePointL<L>, L::Mask)");
    return lighting.sample(s);
  }
}

// The extinction at data values (0 where a value is NaN or infinite).
template <class L, class Sampler>
PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Float sample_extinction(const TransferFunctionView& tf,
                                                                      const Sampler& sampler,
                                                                      typename L::Float value,
                                                                      typename TransferFunctionView::Place<L>& at) {
  using F = typename L::Float;
  if (sampler.all_finite()) {
    at = tf.locate<L>(value);
    return tf.sigma_t<L>(at);
  }
  const auto finite_value = finite(value);
  at = tf.locate<L>(select(finite_value, value, F(0.0f)));
  return select(finite_value, tf.sigma_t<L>(at), F(0.0f));
}

// The part of a ray inside the volume box and the clip planes, within [t_min, t_max].
PENUMBRA_HD inline Interval volume_interval(const RenderView& v, const Ray& ray, float t_min, float t_max) {
  return clip_interval(ray, v.clip_planes, v.clip_plane_count, intersect_box(ray, v.box, t_min, t_max));
}

// Optical depth beyond which transmittance counts as zero (e^-11.5 ~ 1e-5).
inline constexpr float kMaxOpticalDepth = 11.5f;

// Transmittance exp(-integral sigma_t) from each ray's origin along its
// direction up to t_max (the volume boundary or a point light), with sigma_t
// scaled by density_scale, for the W rays of `rays` whose lane is on.
// Respects clip planes; skips empty macrocells.
template <class L, class Sampler>
PENUMBRA_HD PENUMBRA_OUTLINED_MARCH typename L::Float
march_transmittance(const RenderView& v, const Sampler& sampler, const Ray* rays, const float* t_max,
                    float density_scale, typename L::Mask lanes, RayStats& stats) {
  using F = typename L::Float;
  using V = typename L::Vec3;
  using M = typename L::Mask;
  constexpr int W = L::kWidth;
  if (density_scale <= 0.0f) return F(1.0f);
  SampleGrid grids[W];
  vec3 origins[W], directions[W];
  for (int i = 0; i < W; ++i) {
    grids[i] = SampleGrid(volume_interval(v, rays[i], 0.0f, t_max[i]), v.step, 0.5f);
    origins[i] = v.volume.index_from_world(rays[i].origin);
    directions[i] = rays[i].direction / v.volume.spacing;
  }
  LaneCursor<L> cursor(v, rays, grids, lanes);
  const V o = pack_lanes<L>(origins);
  const V d = pack_lanes<L>(directions);
  const TransferFunctionView tf = v.tf;
  F depth(0.0f);
  std::uint64_t samples = 0;
  F t, length;
  M has;
  while (cursor.next(t, length, has)) {
    samples += std::uint64_t(count_true(has));
    const F value = sampler.template sample<L>(o + t * d);
    typename TransferFunctionView::Place<L> at;
    depth += select(has, sample_extinction<L>(tf, sampler, value, at) * length, F(0.0f));
    const M opaque = has & (depth * density_scale >= kMaxOpticalDepth);
    if (any(opaque)) cursor.stop(opaque);
  }
  stats.samples += samples;
  depth *= density_scale;
  return select(depth < kMaxOpticalDepth, exp_nonpositive(-depth), F(0.0f));
}

// One ray.
template <class Sampler>
PENUMBRA_HD float march_transmittance(const RenderView& v, const Sampler& sampler, const Ray& ray, float t_max,
                                      float density_scale, RayStats& stats) {
  return march_transmittance<ScalarLanes>(v, sampler, &ray, &t_max, density_scale, true, stats);
}

// The same, dispatching on the voxel type (one switch per ray). Device code
// switches per sample instead (AnyVoxelSampler, uniform across a warp): one
// instance of the loop rather than one per voxel type keeps CUDA compile
// time down.
PENUMBRA_HD inline float march_transmittance(const RenderView& v, const Ray& ray, float t_max, float density_scale,
                                             RayStats& stats) {
#if defined(__CUDA_ARCH__)
  const AnyVoxelSampler sampler(v.volume.data, v.volume.dims, v.volume.type);
  return march_transmittance(v, sampler, ray, t_max, density_scale, stats);
#else
  return with_sampler(v.volume, [&](const auto& sampler) {
    return march_transmittance(v, sampler, ray, t_max, density_scale, stats);
  });
#endif
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

// Front-to-back compositing of a stream of viewing rays, L::kWidth at a
// time: `rays` gives them (bool next(Ray&, float& sample_offset, int& id))
// and takes each one's linear rgb and accumulated opacity (1 where an
// opaque plane was reached) when it ends (void finish(int id, vec4)). A lane
// whose ray ends starts the next ray of the stream at once, so lanes stay
// busy however different the rays' lengths are.
template <class L, class Sampler, class Lighting, class Rays>
PENUMBRA_HD void march_rays(const RenderView& v, const Sampler& sampler, Rays& rays, const Lighting& lighting,
                            RayStats& stats) {
  using F = typename L::Float;
  using V = typename L::Vec3;
  using M = typename L::Mask;
  constexpr int W = L::kWidth;
  // Finished lanes take new rays when this many are idle (or at once when the
  // stream has no rays left). W, i.e. refill when the whole packet is done,
  // measured fastest: a partial restart (W / 4) cost more in reloading the
  // packet than it won in lane utilisation (docs/PERFORMANCE.md, issue 14).
  constexpr int kRestartLanes = W;
  // Per lane: the ray, where it meets a plane, and the packet values (as
  // columns: x[i], y[i], z[i]) to reload after a restart.
  Ray lane_ray[W];
  int lane_id[W] = {}, lane_plane[W] = {};
  float lane_t_plane[W] = {};
  float columns[12][W] = {};  // index-space origin and direction, world origin and direction
  float red[W], green[W], blue[W], transmittances[W];
  std::uint32_t occupied = 0;

  LaneCursor<L> cursor(v, v.step);
  V o(0.0f), d(0.0f), world_origin(0.0f), world_direction(0.0f), color(0.0f);
  F transmittance(1.0f);
  M terminated(false);
  const TransferFunctionView tf = v.tf;
  const float min_transmittance = 1.0f - v.ert_threshold;
  std::uint64_t samples = 0, steps = 0;
  std::uint32_t finished = (1u << W) - 1u;  // every lane starts a ray
  bool more = true;
  for (;;) {
    if (finished != 0 && (!more || bit_count(finished) >= kRestartLanes)) {
      // End the rays of the finished lanes (behind an early termination
      // nothing; else the opaque plane a ray reached or the background) and
      // start the next rays of the stream on them.
      L::store(color.x, red);
      L::store(color.y, green);
      L::store(color.z, blue);
      L::store(transmittance, transmittances);
      std::uint32_t stopped = L::bits(terminated);
      cursor.begin_starts();
      for (std::uint32_t todo = finished; todo != 0; todo &= todo - 1) {
        const int i = lowest_bit(todo);
        if ((occupied >> i) & 1u) {
          const vec3 c(red[i], green[i], blue[i]);
          const float tr = transmittances[i];
          if ((stopped >> i) & 1u) {
            rays.finish(lane_id[i], vec4(c, 1.0f - tr));
          } else if (lane_plane[i] >= 0) {
            const Ray& r = lane_ray[i];
            const vec3 lit = lighting.plane(PlaneHit{r.at(lane_t_plane[i]), lane_plane[i], r.direction});
            rays.finish(lane_id[i], vec4(c + tr * lit, 1.0f));
          } else {
            rays.finish(lane_id[i], vec4(c + tr * v.background, 1.0f - tr));
          }
        }
        float offset = 0.5f;
        if (!rays.next(lane_ray[i], offset, lane_id[i])) {
          occupied &= ~(1u << i);
          continue;
        }
        occupied |= 1u << i;
        const Ray& r = lane_ray[i];
        lane_plane[i] = nearest_plane(v, r, kInfinity, lane_t_plane[i]);
        cursor.start(i, r, SampleGrid(volume_interval(v, r, 0.0f, lane_t_plane[i]), v.step, offset));
        const vec3 values[4] = {v.volume.index_from_world(r.origin), r.direction / v.volume.spacing, r.origin,
                                r.direction};
        for (int c = 0; c < 4; ++c) {
          columns[3 * c][i] = values[c].x;
          columns[3 * c + 1][i] = values[c].y;
          columns[3 * c + 2][i] = values[c].z;
        }
        red[i] = green[i] = blue[i] = 0.0f;
        transmittances[i] = 1.0f;
        stopped &= ~(1u << i);
      }
      cursor.end_starts();
      o = V(L::load(columns[0]), L::load(columns[1]), L::load(columns[2]));
      d = V(L::load(columns[3]), L::load(columns[4]), L::load(columns[5]));
      world_origin = V(L::load(columns[6]), L::load(columns[7]), L::load(columns[8]));
      world_direction = V(L::load(columns[9]), L::load(columns[10]), L::load(columns[11]));
      color = V(L::load(red), L::load(green), L::load(blue));
      transmittance = L::load(transmittances);
      terminated = L::from_bits(stopped);
      finished = 0;
      if (occupied == 0) break;
    }
    F t, length;
    M has;
    more = cursor.next(t, length, has);
    finished |= cursor.take_finished();
    if (!more) {
      if (finished == 0) break;
      continue;
    }
    samples += std::uint64_t(count_true(has));
    ++steps;
    const V p = o + t * d;
    const GridCell<L> cell(sampler.grid, p);
    const F value = sampler.template sample_at<L>(cell);
    typename TransferFunctionView::Place<L> at;
    const F sigma_t = sample_extinction<L>(tf, sampler, value, at);
    const M lit = has & (sigma_t > 0.0f);
    if (none(lit)) continue;
    const F alpha = 1.0f - exp_nonpositive(-sigma_t * length);
    const SamplePointL<L> s{world_origin + t * world_direction, p, value, tf.color<L>(at), sigma_t, world_direction,
                            &cell};
    color += select(lit, (transmittance * alpha) * light_sample<L>(lighting, s, lit), V(0.0f));
    transmittance = select(lit, transmittance * (1.0f - alpha), transmittance);
    const M done = lit & (transmittance <= min_transmittance);
    if (any(done)) {
      terminated = terminated | done;  // early ray termination
      cursor.stop(done);
      finished |= cursor.take_finished();
    }
  }
  stats.samples += samples;
  stats.steps += steps;
}

// A stream of `count` given rays (march_rays), results into out[i].
struct RayList {
  const Ray* rays;
  const float* offsets;
  vec4* out;
  int count;
  int taken = 0;
  PENUMBRA_HD bool next(Ray& ray, float& offset, int& id) {
    if (taken >= count) return false;
    ray = rays[taken];
    offset = offsets[taken];
    id = taken++;
    return true;
  }
  PENUMBRA_HD void finish(int id, vec4 result) { out[id] = result; }
};

// Front-to-back compositing of one viewing ray. Returns linear rgb and the
// accumulated opacity (1 where an opaque plane was reached).
template <class Sampler, class Lighting>
PENUMBRA_HD vec4 march_ray(const RenderView& v, const Sampler& sampler, const Ray& ray, float offset,
                           const Lighting& lighting, RayStats& stats) {
  vec4 out;
  RayList list{&ray, &offset, &out, 1};
  march_rays<ScalarLanes>(v, sampler, list, lighting, stats);
  return out;
}

}  // namespace penumbra

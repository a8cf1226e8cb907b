#pragma once
// IPSVI's piecewise integration (Sundén et al. 2011, section 4.4,
// castLightRaySeg): the optical depth of the short stretch of light ray from
// a point back toward the light to where the illumination cache's value
// holds. Same step, sample placement (segment midpoints), clip planes and TF
// as a shadow ray (march.h), so a cache that starts at the light's side of
// the box composes to exactly the shadow ray's transmittance.
//
// One march can report the optical depth at several lengths ("checkpoints"):
// a sample reading four cache texels written at four depths needs the
// segment back to each of them.
//
// With Emission (the paper's light model, light_model.h) it also reports
// the colour the stretch adds to the light, Eq. 3's integral
// T(s', from) tau(s') c(s') ds' over it: the segments' TF colours composited
// front to back as seen from `from`, so that the light at `from` is
// exp(-direct) times the light at the far end plus `emitted`.
#include "penumbra/render/march.h"
#include "penumbra/techniques/ipsvi/forward_scattering.h"

namespace penumbra {

#if defined(__GNUC__) && !defined(__CUDACC__)
#define PENUMBRA_FORCE_INLINE_LAMBDA __attribute__((always_inline))
#else
#define PENUMBRA_FORCE_INLINE_LAMBDA
#endif

struct OpticalDepth {
  float direct = 0.0f;  // integral of sigma_t
  vec3 diffuse{0.0f};   // integral of the diffuse part's extinction (forward_scattering.h)
  vec3 emitted{0.0f};   // with emission: the colour the stretch adds to the light (Eq. 3)
};

// Segments up to this many steps are marched sample by sample when one ray
// is marched alone; longer ones (a texel nobody has written yet, whose depth
// is the box entry), and every packet, skip empty macrocells with the
// shared cursor.
inline constexpr int kDirectSegmentSteps = 8;

// The most checkpoints one march reports: four cache texels and the diffuse
// part's mean depth (ipsvi_ray.h).
inline constexpr int kMaxSegmentCheckpoints = 5;

// OpticalDepth on lanes.
template <class L> struct OpticalDepthL {
  typename L::Float direct;
  typename L::Vec3 diffuse, emitted;
};

// The light segments of L::kWidth points, lane i from rays[i].origin along
// rays[i].direction (toward the light), for the lanes on in `lanes`:
// depth[j] = optical depth over [0, lengths[j * L::kWidth + i]] (j < count;
// lanes may leave checkpoints unused at length 0). A checkpoint inside a
// segment of the march gets the part of that segment before it. `samples`
// counts the samples taken. One ray is the one-lane instance (below).
// (Emission is a template parameter so that the grey model's march stays
// free of the colour terms.)
template <bool Emission, class L, class Sampler>
PENUMBRA_HD void light_segment_depths_lanes(const RenderView& v, const Sampler& sampler, const Ray* rays,
                                            const float* lengths, int count, typename L::Mask lanes,
                                            const ForwardScattering& scattering, OpticalDepthL<L>* depth,
                                            std::uint64_t& samples) {
  using F = typename L::Float;
  using V = typename L::Vec3;
  using M = typename L::Mask;
  constexpr int W = L::kWidth;
  SampleGrid grids[W];
  vec3 origins[W], directions[W];
  float starts[W];
  const std::uint32_t on = L::bits(lanes);
  for (int i = 0; i < W; ++i) {
    float longest = 0.0f;
    for (int j = 0; j < count; ++j) longest = glm::max(longest, lengths[j * W + i]);
    grids[i] = ((on >> i) & 1u) ? SampleGrid(volume_interval(v, rays[i], 0.0f, longest), v.step, 0.5f) : SampleGrid();
    origins[i] = v.volume.index_from_world(rays[i].origin);
    directions[i] = rays[i].direction / v.volume.spacing;
    starts[i] = grids[i].t0;
  }
  const V o = pack_lanes<L>(origins);
  const V d = pack_lanes<L>(directions);
  const F t0 = L::load(starts);
  const TransferFunctionView tf = v.tf;
  const bool diffuse = scattering.has_diffuse();
  F checkpoint[kMaxSegmentCheckpoints];
  M passed[kMaxSegmentCheckpoints];
  for (int j = 0; j < count; ++j) {
    checkpoint[j] = L::load(lengths + j * W);
    passed[j] = M(false);
    depth[j] = OpticalDepthL<L>{F(0.0f), V(0.0f), V(0.0f)};
  }
  F total_direct(0.0f);
  V total_diffuse(0.0f), total_emitted(0.0f);
  std::uint64_t taken = 0;
  // Adds the segment [start, start + length) with its sample at t for the
  // lanes in `has`; returns the lanes whose light is gone, after which the
  // rest of their march changes nothing.
  auto add = [&](F t, F length, F start, M has) PENUMBRA_FORCE_INLINE_LAMBDA {
    taken += std::uint64_t(count_true(has));
    const F value = sampler.template sample<L>(o + t * d);
    typename TransferFunctionView::Place<L> at;
    const F sigma = sample_extinction<L>(tf, sampler, value, at);
    V color(0.0f);
    if (Emission || diffuse) {
      color = tf.color<L>(at);
      if (!Sampler::kAlwaysFinite && !sampler.all_finite()) color = select(finite(value), color, V(0.0f));
    }
    const F end = start + length;
    const V ext = diffuse ? scattering.diffuse_extinction<L>(color, sigma) : V(0.0f);
    // Emission: what reaches the segment's origin of the colour of [start, start + part].
    auto emitted = [&](F part) {
      return (exp_nonpositive(-total_direct) * (F(1.0f) - exp_nonpositive(-sigma * part))) *
             clamp(color, V(0.0f), V(1.0f));
    };
    for (int j = 0; j < count; ++j) {
      const M now = has & !passed[j] & (checkpoint[j] < end);
      if (none(now)) continue;
      const F part = max(checkpoint[j] - start, F(0.0f));
      depth[j].direct = select(now, total_direct + sigma * part, depth[j].direct);
      if (diffuse) depth[j].diffuse = select(now, total_diffuse + ext * part, depth[j].diffuse);
      if constexpr (Emission) depth[j].emitted = select(now, total_emitted + emitted(part), depth[j].emitted);
      passed[j] = passed[j] | now;
    }
    if constexpr (Emission) total_emitted = select(has, total_emitted + emitted(length), total_emitted);
    total_direct = select(has, total_direct + sigma * length, total_direct);
    if (diffuse) total_diffuse = select(has, total_diffuse + ext * length, total_diffuse);
    return diffuse ? M(false) : (has & !(total_direct < kMaxOpticalDepth));
  };
  if (W == 1 && grids[0].count <= kDirectSegmentSteps) {
    const SampleGrid& grid = grids[0];
    for (int k = 0; k < grid.count; ++k) {
      if (any(add(F(grid.position(k)), F(grid.length(k)), F(grid.start(k)), M(true)))) break;
    }
  } else {
    LaneCursor<L> cursor(v, rays, grids, lanes);
    F t, length;
    M has;
    while (cursor.next(t, length, has)) {
      const F start = t0 + to_float(cursor.sample_index()) * v.step;
      const M gone = add(t, length, start, has);
      if (any(gone)) cursor.stop(gone);
    }
  }
  for (int j = 0; j < count; ++j) {
    depth[j].direct = select(passed[j], depth[j].direct, total_direct);
    depth[j].diffuse = select(passed[j], depth[j].diffuse, total_diffuse);
    depth[j].emitted = select(passed[j], depth[j].emitted, total_emitted);
  }
  samples += taken;
}

// depth[i] = optical depth over [0, lengths[i]] from `from` along `to_light`
// (count <= kMaxSegmentCheckpoints): the one-lane instance.
template <bool Emission = false, class Sampler>
PENUMBRA_HD void light_segment_depths(const RenderView& v, const Sampler& sampler, vec3 from, vec3 to_light,
                                      const float* lengths, int count, const ForwardScattering& scattering,
                                      OpticalDepth* depth, std::uint64_t& samples) {
  const Ray ray{from, to_light};
  OpticalDepthL<ScalarLanes> lane_depth[kMaxSegmentCheckpoints];
  light_segment_depths_lanes<Emission, ScalarLanes>(v, sampler, &ray, lengths, count, true, scattering, lane_depth,
                                                    samples);
  for (int j = 0; j < count; ++j) {
    depth[j] = OpticalDepth{lane_depth[j].direct, lane_depth[j].diffuse, lane_depth[j].emitted};
  }
}

template <bool Emission = false, class Sampler>
PENUMBRA_HD OpticalDepth light_segment_depth(const RenderView& v, const Sampler& sampler, vec3 from, vec3 to_light,
                                             float length, const ForwardScattering& scattering,
                                             std::uint64_t& samples) {
  OpticalDepth depth;
  light_segment_depths<Emission>(v, sampler, from, to_light, &length, 1, scattering, &depth, samples);
  return depth;
}

}  // namespace penumbra

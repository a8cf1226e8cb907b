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

// Segments up to this many steps are marched sample by sample; longer ones
// (a texel nobody has written yet, whose depth is the box entry) skip empty
// macrocells with the shared cursor.
inline constexpr int kDirectSegmentSteps = 8;

// depth[i] = optical depth over [0, lengths[i]] from `from` along `to_light`
// (count <= 8). A checkpoint inside a segment of the march gets the part of
// that segment before it.
// (Emission is a template parameter so that the grey model's march stays
// the code it was, to the bit.)
template <bool Emission = false, class Sampler>
PENUMBRA_HD void light_segment_depths(const RenderView& v, const Sampler& sampler, vec3 from, vec3 to_light,
                                      const float* lengths, int count, const ForwardScattering& scattering,
                                      OpticalDepth* depth, std::uint64_t& samples) {
  // Checkpoints in increasing length, so the march passes them in order.
  int order[8];
  float longest = 0.0f;
  for (int i = 0; i < count; ++i) {
    int j = i;
    while (j > 0 && lengths[order[j - 1]] > lengths[i]) {
      order[j] = order[j - 1];
      --j;
    }
    order[j] = i;
    longest = glm::max(longest, lengths[i]);
  }
  const Ray ray{from, to_light};
  const SampleGrid grid(volume_interval(v, ray, 0.0f, longest), v.step, 0.5f);
  const vec3 o = v.volume.index_from_world(from);
  const vec3 d = to_light / v.volume.spacing;
  const TransferFunctionView tf = v.tf;
  const bool diffuse = scattering.has_diffuse();
  OpticalDepth total;
  int next = 0;  // the first checkpoint not yet passed
  std::uint64_t taken = 0;
  // Adds segment k (sample at t); false once the light is gone, after which
  // the rest of the segment changes nothing.
  auto add = [&](int k, float t) PENUMBRA_FORCE_INLINE_LAMBDA {
    ++taken;
    const float value = sampler(o + t * d);
    const vec4 c = Sampler::kAlwaysFinite ? tf.lookup_finite(value) : tf.lookup(value);
    const float start = grid.start(k), end = start + grid.length(k);
    const vec3 ext = diffuse ? scattering.diffuse_extinction(vec3(c), c.a) : vec3(0.0f);
    // Emission: what reaches `from` of the colour of [start, start + part].
    auto emitted = [&](float part) {
      return (exp_nonpositive(-total.direct) * (1.0f - exp_nonpositive(-c.a * part))) *
             glm::clamp(vec3(c), vec3(0.0f), vec3(1.0f));
    };
    while (next < count && lengths[order[next]] < end) {
      const float part = glm::max(lengths[order[next]] - start, 0.0f);
      depth[order[next]].direct = total.direct + c.a * part;
      depth[order[next]].diffuse = total.diffuse + ext * part;
      if constexpr (Emission) depth[order[next]].emitted = total.emitted + emitted(part);
      ++next;
    }
    if constexpr (Emission) total.emitted += emitted(end - start);
    total.direct += c.a * (end - start);
    total.diffuse += ext * (end - start);
    return diffuse || total.direct < kMaxOpticalDepth;
  };
  if (grid.count <= kDirectSegmentSteps) {
    for (int k = 0; k < grid.count && add(k, grid.position(k)); ++k) {
    }
  } else {
    SampleCursor cursor(v, ray, grid);
    int k;
    float t;
    while (cursor.next(k, t) && add(k, t)) {
    }
  }
  for (; next < count; ++next) depth[order[next]] = total;
  samples += taken;
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

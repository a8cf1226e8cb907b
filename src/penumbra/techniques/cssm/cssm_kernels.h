#pragma once
// cssm kernels (Weidner & Linsen 2018, Tables 1 and 2).
//
// Generation (Table 1): a photon per texel and channel walks the light ray's
// segments; in segment i it is stopped with probability
// rho_i,lambda = alpha_i (1 - t_i,lambda) (light_ray.h), decided against one
// random threshold r_i per segment shared by the three channels; the texel
// keeps the first stopping depth per channel (+inf: never stopped) and the
// walk ends once all three are set.
// penumbra stores, as that depth, a uniformly random point of the stopping
// segment (one more random number, shared by the channels stopping there)
// rather than a fixed point of it: then P(depth > z) is exactly the
// continuous piecewise-linear transmittance at z (light_ray.h), not a
// staircase with a step per segment.
//
// Query (Table 2): the average over m offsets Delta_j of the per-channel
// tests "stored depth > sample depth". Each test is an unbiased Bernoulli
// estimate of the transmittance of its texel's ray at that depth, so the
// expected visibility is the transmittance averaged over the m texels.
#include "penumbra/render/lighting.h"
#include "penumbra/base/rng.h"
#include "penumbra/techniques/cssm/cssm_offsets.h"
#include "penumbra/techniques/light_space/light_map.h"
#include "penumbra/techniques/light_space/light_ray.h"

namespace penumbra {

// The random stream of one texel of one light's map for a seed.
PENUMBRA_HD inline Pcg32 cssm_texel_rng(std::uint32_t seed, int light, std::int64_t texel) {
  const std::uint64_t key =
      mix_bits(mix_bits((std::uint64_t(seed) << 20) ^ std::uint64_t(light)) + std::uint64_t(texel));
  return Pcg32(key, mix_bits(key ^ 0x9e3779b97f4a7c15ULL));
}

// Per-channel stopping depths of one texel's photons.
template <class Sampler>
PENUMBRA_HD vec3 cssm_texel(const RenderView& v, const Sampler& sampler, const Ray& ray, bool colored, Pcg32& rng) {
  vec3 depth(kInfinity);
  march_light_ray(v, sampler, ray, kInfinity, [&](const LightSegment& s) {
    const float r = rng.next_float();
    const vec3 rho = stop_probability(s, colored);
    float z = 0.0f;
    bool drawn = false;  // the stopping point inside this segment, once a channel needs it
    bool open = false;   // some channel still unset
    for (int c = 0; c < 3; ++c) {
      if (depth[c] != kInfinity) continue;
      if (rho[c] > r) {
        if (!drawn) z = s.start + rng.next_float() * s.length;
        drawn = true;
        depth[c] = z;
      } else {
        open = true;
      }
    }
    return open;
  });
  return depth;
}

// One CSSM for light number `light` with projection `p` (host).
inline LightMap build_cssm(const RenderView& v, const LightProjection& p, std::uint32_t seed, int light, bool colored) {
  LightMap map("colored stochastic shadow map", p, 3);
  with_sampler(v.volume, [&](const auto& sampler) {
    map.fill([&](const Ray& ray, std::int64_t index, float* texel) {
      Pcg32 rng = cssm_texel_rng(seed, light, index);
      const vec3 depth = cssm_texel(v, sampler, ray, colored, rng);
      texel[0] = depth.r;
      texel[1] = depth.g;
      texel[2] = depth.b;
    });
    return 0;
  });
  return map;
}

// Visibility toward light `light`: the fraction of the m offset tests that
// find the sample in front of the stored depth, per channel. Offsets are in
// texels of a 1024^2 map and scale with each map's resolution, so the
// filter covers the same part of the light's view at every resolution.
struct CssmVisibility {
  const LightMapView* maps;
  vec2 offsets[kMaxCssmOffsets];  // texels of a kCssmOffsetResolution map
  int offset_count;

  // Offset j in texels of `map`.
  PENUMBRA_HD vec2 offset(const LightMapView& map, int j) const {
    return offsets[j] * (float(map.projection.resolution) / kCssmOffsetResolution);
  }

  PENUMBRA_HD vec3 operator()(int light, vec3 p, const LightSample& ls) const {
    return lanes<ScalarLanes>(light, p, ls, true);
  }

  template <class L>
  PENUMBRA_HD typename L::Vec3 lanes(int light, const typename L::Vec3& p, const LightSampleL<L>& ls,
                                     typename L::Mask active) const {
    using F = typename L::Float;
    using X = typename L::Index;
    using V = typename L::Vec3;
    const LightMapView& map = maps[light];
    if constexpr (L::kWidth > 1) {
      if (!map.fits_packets()) return L::scalarize(*this, light, p, ls, active);
    }
    LightMapPointL<L> q;
    const auto seen = map.projection.locate<L>(p, q);
    if (none(seen)) return V(1.0f);
    V lit(0.0f);
    for (int j = 0; j < offset_count; ++j) {
      const vec2 o = offset(map, j);
      typename L::Mask inside;
      const X at = map.texel_offset<L>(q.face, to_int(floor(q.x + o.x)), to_int(floor(q.y + o.y)), inside);
      const auto in_front = [&](int channel) {
        return select((!inside) | (gather(map.texels, at + X(channel)) > q.depth), F(1.0f), F(0.0f));
      };
      lit += V(in_front(0), in_front(1), in_front(2));
    }
    return select(seen, lit / float(offset_count), V(1.0f));
  }
};

// The first `count` offsets of the paper's list, times `scale`.
inline CssmVisibility make_cssm_visibility(const LightMapView* maps, int count, float scale) {
  CssmVisibility v{maps, {}, count};
  for (int j = 0; j < count; ++j) v.offsets[j] = scale * vec2(float(kCssmOffsets[j][0]), float(kCssmOffsets[j][1]));
  return v;
}

PENUMBRA_PACKET_LIGHTING(ScatteringLighting<CssmVisibility>);

}  // namespace penumbra

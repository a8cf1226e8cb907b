#pragma once
// Occlusion queries against the moment pyramid (Penner & Mitchell 2008,
// section 4.3, Fig. 7). Every query takes t, the normalised value whose
// exceedance counts as occlusion: for a surface point the value half a voxel
// under the surface, which for a surface on a partial-volume ramp is closer to
// the occluding material's own value than the iso-value is.
//
// Ambient occlusion: one sample in each of the first four levels, centred
// ao_offset sigmas of that level out along the normal (so each spherical
// region lies above the surface, Fig. 6), combined by max (the paper), mean,
// or product of the levels' unoccluded fractions (nested shells of the
// surroundings, each letting through its share, as the soft-shadow march).
// Soft shadows (issue 17): a march toward the light, four samples per
// iteration, with level log2(d tan(theta) / (kConeSigmas sigma0)) at distance
// d (a region of radius kConeSigmas sigma as wide as the light's cone there,
// at least level 0) and steps as long as the level's sigma. Unlike the paper's "most
// occlusion along the ray" (which lets a thin plate through: a one-voxel plate
// fills a fifth of a two-sigma region at best), the samples' transmittances
// are multiplied, each raised to its step over kShadowSlab level-0 sigmas:
// successive regions overlap, and an opaque occluder's share of a region is
// its thickness over the region's depth, so the share per unit of march must
// be weighed against a fixed length (an exponent of step / (kShadowSlab
// sigma_level), as before, let a plate through more the wider the cone: the
// 16-degree penumbra came out 2.5 times the 8-degree one). The shadow query
// is the iso-value (every occluder above it blocks light, also one less dense
// than the receiving surface), and a region whose maximum (the pyramid's
// maximum grids) stays below it occludes nothing. Near the surface a region
// overlaps the receiver's own material: each sample removes from its moments
// the share of the half-space under the tangent plane (Gaussian weight
// Phi(-h / sigma) at height h), as if the receiver were locally flat; the
// rest is estimated by a two-valued fit (shadow_occlusion), since
// Chebyshev's bound, about m / t^2 for a small share m, multiplied along the
// march, darkened lit surfaces (issue 17: the head CT's skull at 0.67
// against the cone's 0.89).
#include "penumbra/base/ray.h"
#include "penumbra/scene/light.h"
#include "penumbra/techniques/occlusion_map/moment_bounds.h"
#include "penumbra/techniques/occlusion_map/moment_pyramid_view.h"

#include <cmath>
#include <cstdint>

namespace penumbra {

inline constexpr int kAmbientOcclusionLevels = 4;
enum class AoCombine : std::uint8_t { Max, Mean, Product };
// Thickness, in level-0 sigmas, of the slab of the light cone that a full
// share of occluders in one soft-shadow sample stands for (the exponent of its
// transmittance is step / (kShadowSlab sigma0)), and the cone's radius in
// sigmas of the region that stands for it. Both checked by the thin-plate and
// penumbra tests against a brute-force cone (occlusion_reference_test.cpp;
// docs/PERFORMANCE.md, issue 17 section): 0.45 lets 7 % through a one-voxel
// plate, and the penumbrae of 8- and 16-degree lights come out 0.97x and
// 1.01x the reference's width with a cone of 1.5 sigmas.
inline constexpr float kShadowSlab = 0.45f;
inline constexpr float kConeSigmas = 1.5f;
// Transmittance below which the march stops (the light is gone).
inline constexpr float kShadowCutoff = 1e-3f;

template <int K> struct OcclusionQueries {
  MomentPyramidView<K> pyramid;
  Box3 box;                // the volume's world box: nothing occludes outside it
  float ao_offset = 2.0f;  // sigmas of each level along the normal
  AoCombine ao_combine = AoCombine::Max;  // how the four levels' occlusion combine
  float default_spread = 0.0f;  // tan(angular radius) for lights without a size
  float forced_spread = -1.0f;  // >= 0: the tan(angular radius) of every light (an explicit light_size_deg)

  // Whether packets' 32-bit gather offsets reach every node of the pyramid
  // (level 0 is the largest).
  bool packets_fit() const {
    if (pyramid.level_count < 1) return false;
    const ivec3 d = pyramid.levels[0].dims;
    return std::uint64_t(d.x) * std::uint64_t(d.y) * std::uint64_t(d.z) * K < (std::uint64_t(1) << 31) - 64;
  }

  // Share of a Gaussian region (centre c, standard deviation sigma) inside
  // the volume's box. Outside the box there is nothing, so the occlusion of a
  // region is its inside part's (what the pyramid's edge-renormalised nodes,
  // nearest to c, hold) times this share. Without it a region out past the
  // border would see the border voxels' region, and a surface facing out of
  // the volume would be occluded by what lies behind it.
  template <class L>
  PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Float inside_share_lanes(const typename L::Vec3& c,
                                                                        typename L::Float sigma) const {
    using F = typename L::Float;
    const F scale = 1.0f / (1.41421356f * sigma);
    F share(1.0f);
    typename L::Mask outside(false);
    for (int a = 0; a < 3; ++a) {
      // The share along an axis is (erf(above) - erf(below)) / 2, i.e.
      // (erfc(below) - erfc(above)) / 2. erf is exactly +-1 in float beyond
      // 4 (1 - erf(4) = 1.5e-8), so an axis along which the centre lies more
      // than 4 / scale inside both faces contributes exactly 1 and one that
      // far outside a face exactly 0, without the erfc calls (most samples
      // of a march lie inside).
      const F above = (box.upper[a] - c[a]) * scale, below = (box.lower[a] - c[a]) * scale;
      outside = outside | (above < -4.0f) | (below > 4.0f);
      const auto inner = (above > 4.0f) & (below < -4.0f);
      if (all(inner | outside)) continue;
      share = select(inner, share, share * (0.5f * (erfc_lanes(below) - erfc_lanes(above))));
    }
    return select(outside, F(0.0f), clamp(share, F(0.0f), F(1.0f)));
  }
  PENUMBRA_HD float inside_share(vec3 c, float sigma) const { return inside_share_lanes<ScalarLanes>(c, sigma); }

  // Occluded fraction of level `level`'s region around c for query t: the
  // bound from its moments, and none where the region's maximum stays below
  // t (the moments cannot tell material just under the query from material
  // above it; the maximum can).
  PENUMBRA_HD float occlusion(float level, vec3 c, float t) const {
    return occlusion(level, pyramid.sigma(level), c, t);
  }
  // The same with the level's sigma given.
  PENUMBRA_HD float occlusion(float level, float sigma, vec3 c, float t) const {
    return occlusion_lanes<ScalarLanes>(level, sigma, c, t, true);
  }
  // The same on any lane type, each lane with its own query t; 0 on lanes
  // that are off. Four moments only on ScalarLanes.
  template <class L>
  PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Float occlusion_lanes(typename L::Float level, typename L::Float sigma,
                                                                     const typename L::Vec3& c, typename L::Float t,
                                                                     typename L::Mask active) const {
    using F = typename L::Float;
    using M = typename L::Mask;
    const M occluding = active & (pyramid.template maximum_lanes<L>(level, c, active) >= t);
    if (none(occluding)) return F(0.0f);
    F m[K];
    pyramid.template sample_lanes<L>(level, c, occluding, m);
    F fraction;
    if constexpr (K == 2) {
      fraction = chebyshev_occlusion_lanes<F>(m[0], m[1], t);
    } else {
      static_assert(L::kWidth == 1, "four moments have no packet form");
      fraction = occluded_fraction<K>(vec4(m[0], m[1], m[2], m[3]), t);
    }
    return select(occluding, inside_share_lanes<L>(c, sigma) * fraction, F(0.0f));
  }

  // The soft-shadow sample's occluded fraction of level `level`'s region
  // around c: the share `own` of it (the receiver's half-space) taken out of
  // its moments first, at the receiver's value u_own or the region's maximum
  // if that is higher (the receiver's material is rarely at the value just
  // under its surface: dense bone under a partial-volume rim). With two
  // moments the rest is an estimate, not the bound: the share of the upper
  // atom of the two-valued distribution with the region's mean and variance
  // whose upper atom lies midway between t and the region's maximum M. Its
  // occluders lie in [t, M]; the atom at t is Chebyshev's bound (about
  // m / t^2 for a small occupied share m: four times m at t = 0.5, which
  // the march's product turns into dark lit surfaces), the atom at M the
  // exact share of a two-valued region (which lets occluders just above t
  // through when denser voxels raise M).
  PENUMBRA_HD float shadow_occlusion(float level, vec3 c, float t, float own, float u_own) const {
    return shadow_occlusion(level, pyramid.sigma(level), c, t, own, u_own);
  }
  // The same with the level's sigma given.
  PENUMBRA_HD float shadow_occlusion(float level, float sigma, vec3 c, float t, float own, float u_own) const {
    return shadow_occlusion_lanes<ScalarLanes>(level, sigma, c, t, own, u_own, true);
  }
  // The same on any lane type, each lane at its own (fractional) level; 0 on
  // lanes that are off. Four moments only on ScalarLanes.
  template <class L>
  PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Float shadow_occlusion_lanes(typename L::Float level,
                                                                            typename L::Float sigma,
                                                                            const typename L::Vec3& c, float t,
                                                                            typename L::Float own,
                                                                            typename L::Float u_own,
                                                                            typename L::Mask active) const {
    using F = typename L::Float;
    using M = typename L::Mask;
    const F top = pyramid.template maximum_lanes<L>(level, c, active);
    const M occluding = active & (top >= t);
    if (none(occluding)) return F(0.0f);
    F m[K];
    pyramid.template sample_lanes<L>(level, c, occluding, m);
    const M remove = occluding & (own > 1e-4f);
    if (any(remove)) {
      const F keep = max(1.0f - own, F(1e-3f));
      const F u = max(u_own, top);
      F power = u;
      for (int i = 0; i < K; ++i) {
        m[i] = select(remove, max(m[i] - own * power, F(0.0f)) / keep, m[i]);
        power = power * u;
      }
      m[1] = select(remove, max(m[1], m[0] * m[0]), m[1]);
    }
    F fraction;
    if constexpr (K == 2) {
      // Chebyshev's expression at the atom: the share of the upper atom of
      // the two-valued distribution with these moments (atom > t > mean).
      const F atom = 0.5f * (t + top);
      const F variance = max(m[1] - m[0] * m[0], F(kMinMomentVariance));
      const F d = atom - m[0];
      fraction = select((F(t) <= m[0]) | (atom <= m[0]), F(1.0f), variance / (variance + d * d));
    } else {
      static_assert(L::kWidth == 1, "four moments have no packet form");
      fraction = occluded_fraction<K>(vec4(m[0], m[1], m[2], m[3]), t);
    }
    return select(occluding, inside_share_lanes<L>(c, sigma) * fraction, F(0.0f));
  }

  // Unoccluded fraction of the surroundings of p (unit normal n): 1 - occlusion.
  PENUMBRA_HD float ambient(vec3 p, vec3 n, float t) const { return ambient_lanes<ScalarLanes>(p, n, t, true); }
  // The same for a packet of points, each with its own query (1 on lanes
  // that are off): DVR mode's packets (occlusion_shading.h).
  template <class L>
  PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Float ambient_lanes(const typename L::Vec3& p,
                                                                   const typename L::Vec3& n, typename L::Float t,
                                                                   typename L::Mask active) const {
    using F = typename L::Float;
    F worst(0.0f), sum(0.0f), open(1.0f);
    const int levels = glm::min(kAmbientOcclusionLevels, pyramid.level_count);
    for (int k = 0; k < levels; ++k) {
      const float sigma = pyramid.sigma_at(k);
      const typename L::Vec3 q = p + n * (ao_offset * sigma);
      const F occlusion = occlusion_lanes<L>(F(float(k)), F(sigma), q, t, active);
      worst = max(worst, occlusion);
      sum = sum + occlusion;
      open = open * (1.0f - occlusion);
    }
    switch (ao_combine) {
      case AoCombine::Mean: return 1.0f - sum / float(levels);
      case AoCombine::Product: return open;
      default: return 1.0f - worst;
    }
  }

  // tan of the angular radius of a light seen from p. The cone query is
  // round: an anisotropic Gaussian light takes the radius of equal variance,
  // the root mean square of its two spreads.
  PENUMBRA_HD float light_spread(const Light& light, vec3 p) const {
    if (forced_spread >= 0.0f) return forced_spread;
    switch (light.type) {
      case LightType::Distant: {
        const float x = glm::min(light.angle_deg, 89.0f), y = glm::min(light.spread_y_deg(), 89.0f);
        if (x == y) return glm::tan(glm::radians(x));
        const vec2 t(glm::tan(glm::radians(x)), glm::tan(glm::radians(y)));
        return glm::sqrt(0.5f * glm::dot(t, t));
      }
      case LightType::Sphere:
      case LightType::Disk: {
        const float d = glm::length(light.position - p);
        return d > light.radius ? light.radius / glm::sqrt(d * d - light.radius * light.radius) : 1e3f;
      }
      default: return default_spread;
    }
  }

  // Unoccluded fraction toward a light: the product of the samples'
  // transmittances (1 - occlusion)^(step / (kShadowSlab sigma0)) along the
  // march from p (moved off the surface along n like the first AO sample)
  // toward the light, up to the light or the volume's boundary. t: the
  // query (the iso-value); u_own: the receiver's value under the surface,
  // negative for a receiver with nothing of the volume under it (a plane).
  PENUMBRA_HD float soft_shadow(vec3 p, vec3 n, vec3 to_light, float light_distance, float spread, float t,
                                float u_own) const {
    return soft_shadow_lanes<ScalarLanes>(p, n, to_light, light_distance, spread, t, u_own, true);
  }
  // The same for a packet of points (lanes that are off give 1): the
  // scalar path is its one-lane instance, occlusion-map's packets
  // (occlusion_map_packets.cpp) march 8 or 16 shadow queries at once.
  template <class L>
  PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Float soft_shadow_lanes(
      const typename L::Vec3& p, const typename L::Vec3& n, const typename L::Vec3& to_light,
      typename L::Float light_distance, typename L::Float spread, float t, typename L::Float u_own,
      typename L::Mask active) const {
    using F = typename L::Float;
    using M = typename L::Mask;
    using V = typename L::Vec3;
    const float lift = ao_offset * pyramid.sigma0;  // distance already travelled from p
    const V start = p + n * lift;
    F s(0.0f), end = light_distance;
    box_overlap<L>(box, start, to_light, s, end);
    active = active & (s < end);
    if (none(active)) return F(1.0f);
    const float top = float(pyramid.level_count - 1);
    const float cutoff = glm::log(kShadowCutoff);
    const float slab = kShadowSlab * pyramid.sigma0;
    const float cone = kConeSigmas * pyramid.sigma0;
    F log_transmittance(0.0f);
    M dark(false);  // lanes whose light is gone
    while (any(active)) {
      // Four steps per iteration, as the paper evaluates four in parallel.
      for (int i = 0; i < 4; ++i) {
        const M m = active & (s < end);
        if (none(m)) break;
        const F level = clamp(log2_positive(max((s + lift) * spread / cone, F(1.0f))), F(0.0f), F(top));
        const auto whole = to_int_nonnegative(level);
        const F step = pyramid.sigma0 * float_from_bits((whole + 127) << 23);  // sigma at the whole level
        const F covered = min(step, end - s);
        const V c = start + to_light * s;
        const F sigma = pyramid.sigma0 * exp2_nonnegative(level);
        // The receiver's share; beyond height 2.7 it is under 7e-5, which
        // shadow_occlusion counts as none (own <= 1e-4), so erfc is skipped.
        const F height = dot(c - p, n) / (1.41421356f * sigma);
        const M shared = m & (u_own >= 0.0f) & (height <= 2.7f);
        const F own = any(shared) ? select(shared, 0.5f * erfc_lanes(height), F(0.0f)) : F(0.0f);
        const F occlusion = shadow_occlusion_lanes<L>(level, sigma, c, t, own, u_own, m);
        const M blocked = m & (occlusion >= 1.0f);
        dark = dark | blocked;
        active = active & !blocked;
        const M occluded = m & !blocked & (occlusion > 0.0f);
        if (any(occluded)) {
          const F kept = log_positive(select(occluded, 1.0f - occlusion, F(1.0f)));
          log_transmittance = log_transmittance + select(occluded, covered / slab * kept, F(0.0f));
        }
        s = select(m, s + step, s);
      }
      const M cut = active & (log_transmittance <= cutoff);
      dark = dark | cut;
      active = active & !cut & (s < end);
    }
    return select(dark, F(0.0f), exp_nonpositive(log_transmittance));
  }
};

}  // namespace penumbra

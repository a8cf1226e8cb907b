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

  // Share of a Gaussian region (centre c, standard deviation sigma) inside
  // the volume's box. Outside the box there is nothing, so the occlusion of a
  // region is its inside part's (what the pyramid's edge-renormalised nodes,
  // nearest to c, hold) times this share. Without it a region out past the
  // border would see the border voxels' region, and a surface facing out of
  // the volume would be occluded by what lies behind it.
  PENUMBRA_HD float inside_share(vec3 c, float sigma) const {
    const float scale = 1.0f / (glm::sqrt(2.0f) * sigma);
    float share = 1.0f;
    for (int a = 0; a < 3; ++a) {
      // erf is exactly +-1 in float beyond 4 (1 - erf(4) = 1.5e-8), so an
      // axis along which the centre lies more than 4 / scale inside both
      // faces contributes exactly 1 and one that far outside a face exactly
      // 0, without the erf calls (most samples of a march lie inside).
      const float above = (box.upper[a] - c[a]) * scale, below = (box.lower[a] - c[a]) * scale;
      if (above < -4.0f || below > 4.0f) return 0.0f;
      if (above > 4.0f && below < -4.0f) continue;
      share *= 0.5f * (std::erf(above) - std::erf(below));
    }
    return glm::clamp(share, 0.0f, 1.0f);
  }

  // Occluded fraction of level `level`'s region around c for query t: the
  // bound from its moments, and none where the region's maximum stays below
  // t (the moments cannot tell material just under the query from material
  // above it; the maximum can).
  PENUMBRA_HD float occlusion(float level, vec3 c, float t) const {
    return occlusion(level, pyramid.sigma(level), c, t);
  }
  // The same with the level's sigma given.
  PENUMBRA_HD float occlusion(float level, float sigma, vec3 c, float t) const {
    if (pyramid.maximum(level, c) < t) return 0.0f;
    return inside_share(c, sigma) * occluded_fraction<K>(pyramid.sample(level, c), t);
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
    using Moments = typename MomentPyramidView<K>::Moments;
    const float top = pyramid.maximum(level, c);
    if (top < t) return 0.0f;
    Moments m = pyramid.sample(level, c);
    if (own > 1e-4f) {
      const float keep = glm::max(1.0f - own, 1e-3f);
      const float u = glm::max(u_own, top);
      float power = u;
      for (int i = 0; i < K; ++i) {
        m[i] = glm::max(m[i] - own * power, 0.0f) / keep;
        power *= u;
      }
      m[1] = glm::max(m[1], m[0] * m[0]);
    }
    float fraction;
    if constexpr (K == 2) {
      // Chebyshev's expression at the atom: the share of the upper atom of
      // the two-valued distribution with these moments (atom > t > mean).
      fraction = t <= m[0] ? 1.0f : chebyshev_occlusion(m[0], m[1], 0.5f * (t + top));
    } else {
      fraction = occluded_fraction<K>(m, t);
    }
    return inside_share(c, sigma) * fraction;
  }

  // Unoccluded fraction of the surroundings of p (unit normal n): 1 - occlusion.
  PENUMBRA_HD float ambient(vec3 p, vec3 n, float t) const {
    float worst = 0.0f, sum = 0.0f, open = 1.0f;
    const int levels = glm::min(kAmbientOcclusionLevels, pyramid.level_count);
    for (int k = 0; k < levels; ++k) {
      const float sigma = pyramid.sigma_at(k);
      const vec3 q = p + n * (ao_offset * sigma);
      const float occlusion = this->occlusion(float(k), sigma, q, t);
      worst = glm::max(worst, occlusion);
      sum += occlusion;
      open *= 1.0f - occlusion;
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
    const float lift = ao_offset * pyramid.sigma0;  // distance already travelled from p
    const vec3 start = p + n * lift;
    const Interval inside = intersect_box(Ray{start, to_light}, box, 0.0f, light_distance);
    if (inside.empty()) return 1.0f;
    const float top = float(pyramid.level_count - 1);
    const float cutoff = glm::log(kShadowCutoff);
    float log_transmittance = 0.0f;
    float s = inside.t0;
    while (s < inside.t1) {
      // Four steps per iteration, as the paper evaluates four in parallel.
      for (int i = 0; i < 4 && s < inside.t1; ++i) {
        const float level = glm::clamp(glm::log2(glm::max((s + lift) * spread / (kConeSigmas * pyramid.sigma0), 1.0f)),
                                       0.0f, top);
        const int whole = int(level);  // level >= 0
        const float step = pyramid.sigma_at(whole);
        const float covered = glm::min(step, inside.t1 - s);
        const vec3 c = start + s * to_light;
        const float sigma = level == float(whole) ? step : pyramid.sigma(level);
        // The receiver's share; beyond height 2.7 it is under 7e-5, which
        // shadow_occlusion counts as none (own <= 1e-4), so erfc is skipped.
        const float height = glm::dot(c - p, n) / (glm::sqrt(2.0f) * sigma);
        const float own = u_own < 0.0f || height > 2.7f ? 0.0f : 0.5f * std::erfc(height);
        const float occlusion = shadow_occlusion(level, sigma, c, t, own, u_own);
        if (occlusion >= 1.0f) return 0.0f;
        if (occlusion > 0.0f) log_transmittance += covered / (kShadowSlab * pyramid.sigma0) * glm::log(1.0f - occlusion);
        s += step;
      }
      if (log_transmittance <= cutoff) return 0.0f;
    }
    return glm::exp(log_transmittance);
  }
};

}  // namespace penumbra

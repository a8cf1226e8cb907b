#pragma once
// shadow-map kernels: one depth per texel, a binary depth test per lookup.
#include "penumbra/render/lighting.h"
#include "penumbra/techniques/light_space/light_map.h"
#include "penumbra/techniques/light_space/light_ray.h"
#include "penumbra/techniques/light_space/pcss.h"

namespace penumbra {

// Depth at which the accumulated opacity 1 - prod(1 - alpha_i) along the
// light ray reaches `threshold`: inside the first segment whose sample
// passes it, where the piecewise-linear transmittance (light_ray.h) crosses
// 1 - threshold. +inf when the ray never gets that opaque.
template <class Sampler>
PENUMBRA_HD float shadow_map_depth(const RenderView& v, const Sampler& sampler, const Ray& ray, float threshold) {
  const float target = 1.0f - threshold;
  float transmittance = 1.0f;
  float depth = kInfinity;
  march_light_ray(v, sampler, ray, kInfinity, [&](const LightSegment& s) {
    const float after = transmittance * (1.0f - s.alpha);
    if (after <= target) {
      const float drop = transmittance - after;
      const float f = drop > 0.0f ? (transmittance - target) / drop : 0.0f;
      depth = s.start + glm::clamp(f, 0.0f, 1.0f) * s.length;
      return false;
    }
    transmittance = after;
    return true;
  });
  return depth;
}

// One shadow map for the light of projection `p` (host).
inline LightMap build_shadow_map(const RenderView& v, const LightProjection& p, float threshold) {
  LightMap map("shadow map", p, 1);
  with_sampler(v.volume, [&](const auto& sampler) {
    map.fill(
        [&](const Ray& ray, std::int64_t, float* texel) { texel[0] = shadow_map_depth(v, sampler, ray, threshold); });
    return 0;
  });
  return map;
}

// Largest depth change per texel, in texel footprints, that the
// slope-scaled bias follows (a surface about 83 degrees from facing the
// light); steeper changes are depth discontinuities.
inline constexpr float kShadowMapMaxSlope = 8.0f;

// Visibility toward light `light` with percentage-closer filtering over
// (2 r + 1)^2 texels around the nearest one (r = 0: the plain binary test):
// a texel lights the point when the point lies in front of its stored depth
// plus a bias against self-shadowing; outside the map: lit.
// The bias is a constant (depth_bias) plus a slope-scaled part: on a
// surface inclined to the light the stored depth changes from texel to
// texel, and a tap's texel centre lies up to (r + 1/2) texels (r: its
// Chebyshev distance) from the sample, whose surface lies that much nearer
// or farther: acne stripes on grazing surfaces. Each tap compares the
// sample's depth moved by slope_bias times the stored depth's change from
// the sample to the tap's centre, from the gradient around the sample
// (LightMapView::plane_gradient, capped at kShadowMapMaxSlope footprints
// per texel): for slope_bias 1 the comparison a planar occluder would give
// at the sample's own ray.
// With the PCSS filter on for the light (pcss.on(light), light_space/pcss.h)
// the (2 r + 1)^2 box is replaced by the filter disk sized by the light and
// the blockers' mean depth; each of its taps is the same biased depth test.
struct ShadowMapVisibility {
  const LightMapView* maps;
  // The device copy (backends/device.h).
  template <class Mirror> ShadowMapVisibility on_device(Mirror& m) const {
    ShadowMapVisibility d = *this;
    d.maps = light_maps_on_device(maps, m);
    return d;
  }
  int pcf_radius;
  float bias;  // world units
  float slope_bias = 1.0f;
  Pcss pcss{};  // no light on: the (2 r + 1)^2 filter

  PENUMBRA_HD vec3 operator()(int light, vec3 p, const LightSample& ls) const {
    return lanes<ScalarLanes>(light, p, ls, true);
  }

  template <class L>
  PENUMBRA_HD typename L::Vec3 lanes(int light, const typename L::Vec3& p, const LightSampleL<L>& ls,
                                     typename L::Mask active) const {
    using F = typename L::Float;
    using I = typename L::Int;
    using M = typename L::Mask;
    const LightMapView& map = maps[light];
    if constexpr (L::kWidth > 1) {
      if (!map.fits_packets()) return L::scalarize(*this, light, p, ls, active);
    }
    LightMapPointL<L> q;
    const M seen = map.projection.locate<L>(p, q);
    if (none(seen)) return typename L::Vec3(1.0f);
    const I x = to_int(floor(q.x));
    const I y = to_int(floor(q.y));
    F gx, gy;
    map.receiver_plane<L>(q, 0, kShadowMapMaxSlope, slope_bias, gx, gy);
    const auto test = [&](const I& tx, const I& ty) {
      M inside;
      const auto at = map.texel_offset<L>(q.face, tx, ty, inside);
      const F stored = gather(map.texels, at);
      const F depth = q.depth + gx * (to_float(tx) + 0.5f - q.x) + gy * (to_float(ty) + 0.5f - q.y);
      return select((!inside) | (depth < stored + bias), F(1.0f), F(0.0f));
    };
    if (pcss.on(light)) {
      M blocked;
      const F radius = pcss_radius<L>(pcss, light, map, q, 0, bias, blocked);
      const M shaded = seen & blocked;
      if (none(shaded)) return typename L::Vec3(1.0f);
      return typename L::Vec3(select(shaded, pcss_filter<L, F>(pcss, q, radius, test), F(1.0f)));
    }
    F lit(0.0f);
    for (int dy = -pcf_radius; dy <= pcf_radius; ++dy) {
      for (int dx = -pcf_radius; dx <= pcf_radius; ++dx) {
        M inside;
        const I tx = x + I(dx), ty = y + I(dy);
        const auto at = map.texel_offset<L>(q.face, tx, ty, inside);
        const F stored = gather(map.texels, at);
        const F depth = q.depth + gx * (to_float(tx) + 0.5f - q.x) + gy * (to_float(ty) + 0.5f - q.y);
        lit += select((!inside) | (depth < stored + bias), F(1.0f), F(0.0f));
      }
    }
    const int side = 2 * pcf_radius + 1;
    return typename L::Vec3(select(seen, lit / float(side * side), F(1.0f)));
  }
};

PENUMBRA_PACKET_LIGHTING(ScatteringLighting<ShadowMapVisibility>);
PENUMBRA_DEVICE_LIGHTING(ScatteringLighting<ShadowMapVisibility>);

}  // namespace penumbra

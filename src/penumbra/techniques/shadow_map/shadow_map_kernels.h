#pragma once
// shadow-map kernels: one depth per texel, a binary depth test per lookup.
#include "penumbra/techniques/light_space/light_map.h"
#include "penumbra/techniques/light_space/light_ray.h"

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

// The binary test at one texel: lit when the point lies in front of the
// stored depth (plus a bias against self-shadowing). Outside the map: lit.
PENUMBRA_HD inline float shadow_map_test(const LightMapView& map, int face, int x, int y, float depth, float bias) {
  const float* stored = map.texel(face, x, y);
  return (!stored || depth < stored[0] + bias) ? 1.0f : 0.0f;
}

// Visibility toward light `light` with percentage-closer filtering over
// (2 r + 1)^2 texels around the nearest one (r = 0: the plain binary test).
struct ShadowMapVisibility {
  const LightMapView* maps;
  int pcf_radius;
  float bias;  // world units

  PENUMBRA_HD vec3 operator()(int light, vec3 p, const LightSample&) const {
    const LightMapView& map = maps[light];
    LightMapPoint q;
    if (!map.projection.locate(p, q)) return vec3(1.0f);
    const int x = int(glm::floor(q.texel.x));
    const int y = int(glm::floor(q.texel.y));
    float lit = 0.0f;
    for (int dy = -pcf_radius; dy <= pcf_radius; ++dy) {
      for (int dx = -pcf_radius; dx <= pcf_radius; ++dx)
        lit += shadow_map_test(map, q.face, x + dx, y + dy, q.depth, bias);
    }
    const int side = 2 * pcf_radius + 1;
    return vec3(lit / float(side * side));
  }
};

}  // namespace penumbra

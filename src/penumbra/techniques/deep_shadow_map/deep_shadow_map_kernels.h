#pragma once
// deep-shadow-map kernels: a texel stores N nodes (depth, r, g, b) of its
// light ray's compressed transmittance; a lookup evaluates them at the
// sample's depth.
#include "penumbra/techniques/deep_shadow_map/deep_shadow_compression.h"
#include "penumbra/techniques/light_space/light_map.h"
#include "penumbra/techniques/light_space/light_ray.h"

namespace penumbra {

// Transmittance below which the rest of a light ray is taken as dark (the
// error this adds is far below any compression tolerance).
inline constexpr float kDeepShadowFloor = 1e-4f;

// Marches the light ray, compresses its transmittance (light_ray.h) into
// `node_count` nodes written to `texel` (node_count * 4 floats; unused nodes
// at depth +inf) and returns the tolerance the stored nodes meet.
template <class Sampler>
PENUMBRA_HD float deep_shadow_texel(const RenderView& v, const Sampler& sampler, const Ray& ray, bool colored,
                                    float tolerance, int node_count, float* texel) {
  DeepShadowCompressor compressor(tolerance, node_count);
  vec3 transmittance(1.0f);
  float end = -kInfinity;
  march_light_ray(v, sampler, ray, kInfinity, [&](const LightSegment& s) {
    // A gap of skipped empty space is flat: its start is a breakpoint too.
    if (s.start > end + 1e-3f * s.length) compressor.add(s.start, transmittance);
    transmittance *= 1.0f - stop_probability(s, colored);
    end = s.start + s.length;
    compressor.add(end, transmittance);
    return max_component(transmittance) > kDeepShadowFloor;
  });
  const DeepShadowNodes nodes = compressor.finish();
  vec3 last(1.0f);
  for (int k = 0; k < node_count; ++k) {
    float* node = texel + 4 * k;
    if (k < nodes.count) {
      node[0] = nodes.nodes[k].depth;
      last = nodes.nodes[k].transmittance;
    } else {
      node[0] = kInfinity;
    }
    node[1] = last.r;
    node[2] = last.g;
    node[3] = last.b;
  }
  return nodes.overflowed ? kInfinity : nodes.tolerance;
}

// One deep shadow map for the light of projection `p` (host).
inline LightMap build_deep_shadow_map(const RenderView& v, const LightProjection& p, int node_count, float tolerance,
                                      bool colored) {
  LightMap map("deep shadow map", p, 4 * node_count);
  with_sampler(v.volume, [&](const auto& sampler) {
    map.fill([&](const Ray& ray, std::int64_t, float* texel) {
      deep_shadow_texel(v, sampler, ray, colored, tolerance, node_count, texel);
    });
    return 0;
  });
  return map;
}

// Visibility toward light `light`: the nodes of the nearest texel, or a
// bilinear blend of the four nearest texels' functions at the same depth.
struct DeepShadowVisibility {
  const LightMapView* maps;
  int node_count;
  bool bilinear;

  PENUMBRA_HD vec3 texel_value(const LightMapView& map, int face, int x, int y, float depth) const {
    const float* texel = map.texel(face, x, y);
    return texel ? evaluate_deep_shadow(texel, node_count, depth) : vec3(1.0f);
  }

  PENUMBRA_HD vec3 operator()(int light, vec3 p, const LightSample&) const {
    const LightMapView& map = maps[light];
    LightMapPoint q;
    if (!map.projection.locate(p, q)) return vec3(1.0f);
    if (!bilinear) return texel_value(map, q.face, int(glm::floor(q.texel.x)), int(glm::floor(q.texel.y)), q.depth);
    const vec2 c = q.texel - 0.5f;
    const vec2 base = glm::floor(c);
    const vec2 f = c - base;
    const int x = int(base.x), y = int(base.y);
    const vec3 top =
        glm::mix(texel_value(map, q.face, x, y, q.depth), texel_value(map, q.face, x + 1, y, q.depth), f.x);
    const vec3 bottom =
        glm::mix(texel_value(map, q.face, x, y + 1, q.depth), texel_value(map, q.face, x + 1, y + 1, q.depth), f.x);
    return glm::mix(top, bottom, f.y);
  }
};

}  // namespace penumbra

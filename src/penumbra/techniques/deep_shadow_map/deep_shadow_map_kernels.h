#pragma once
// deep-shadow-map kernels: a texel stores N nodes (depth, r, g, b) of its
// light ray's compressed transmittance; a lookup evaluates them at the
// sample's depth.
#include "penumbra/render/lighting.h"
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

  // The function of texel (x, y) of `face` at `depth`; lit outside the map.
  template <class L>
  PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Vec3 texel_value(const LightMapView& map, typename L::Int face,
                                                                 typename L::Int x, typename L::Int y,
                                                                 typename L::Float depth) const {
    typename L::Mask inside;
    const auto at = map.texel_offset<L>(face, x, y, inside);
    using V = typename L::Vec3;
    return select(inside, evaluate_deep_shadow<L>(map.texels, at, node_count, depth), V(1.0f));
  }

  PENUMBRA_HD vec3 operator()(int light, vec3 p, const LightSample& ls) const {
    return lanes<ScalarLanes>(light, p, ls, true);
  }

  template <class L>
  PENUMBRA_HD typename L::Vec3 lanes(int light, const typename L::Vec3& p, const LightSampleL<L>& ls,
                                     typename L::Mask active) const {
    using F = typename L::Float;
    using I = typename L::Int;
    using V = typename L::Vec3;
    const LightMapView& map = maps[light];
    if constexpr (L::kWidth > 1) {
      if (!map.fits_packets()) return L::scalarize(*this, light, p, ls, active);
    }
    LightMapPointL<L> q;
    const auto seen = map.projection.locate<L>(p, q);
    if (none(seen)) return V(1.0f);
    if (!bilinear) {
      return select(seen, texel_value<L>(map, q.face, to_int(floor(q.x)), to_int(floor(q.y)), q.depth), V(1.0f));
    }
    const F cx = q.x - 0.5f, cy = q.y - 0.5f;
    const F bx = floor(cx), by = floor(cy);
    const F fx = cx - bx, fy = cy - by;
    const I x = to_int(bx), y = to_int(by);
    const V v00 = texel_value<L>(map, q.face, x, y, q.depth);
    const V v10 = texel_value<L>(map, q.face, x + I(1), y, q.depth);
    const V v01 = texel_value<L>(map, q.face, x, y + I(1), q.depth);
    const V v11 = texel_value<L>(map, q.face, x + I(1), y + I(1), q.depth);
    const V top = v00 * (1.0f - fx) + v10 * fx;
    const V bottom = v01 * (1.0f - fx) + v11 * fx;
    return select(seen, top * (1.0f - fy) + bottom * fy, V(1.0f));
  }
};

PENUMBRA_PACKET_LIGHTING(ScatteringLighting<DeepShadowVisibility>);

}  // namespace penumbra

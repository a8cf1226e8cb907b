#pragma once
// deep-shadow-map kernels: a texel stores N nodes (depth, r, g, b) of its
// light ray's compressed transmittance; a lookup evaluates them at the
// sample's depth.
#include "penumbra/render/lighting.h"
#include "penumbra/techniques/deep_shadow_map/deep_shadow_compression.h"
#include "penumbra/techniques/light_space/light_map.h"
#include "penumbra/techniques/light_space/light_ray.h"
#include "penumbra/techniques/light_space/pcss.h"

namespace penumbra {

// Transmittance below which the rest of a light ray is taken as dark (the
// error this adds is far below any compression tolerance).
inline constexpr float kDeepShadowFloor = 1e-4f;

// Marches the light ray, compresses its transmittance (light_ray.h) into
// `node_count` nodes written to `texel` (node_count * 4 floats; unused nodes
// at depth +inf) and returns the tolerance the stored nodes meet.
template <class Sampler>
PENUMBRA_HD float deep_shadow_texel(const RenderView& v, const Sampler& sampler, const Ray& ray,
                                    const ShadowColorModel& colors, float tolerance, int node_count, float* texel) {
  DeepShadowCompressor compressor(tolerance, node_count);
  vec3 transmittance(1.0f);
  float end = -kInfinity;
  march_light_ray(v, sampler, ray, kInfinity, [&](const LightSegment& s) {
    // A gap of skipped empty space is flat: its start is a breakpoint too.
    if (s.start > end + 1e-3f * s.length) compressor.add(s.start, transmittance);
    transmittance *= 1.0f - stop_probability(s, colors);
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
                                      const ShadowColorModel& colors) {
  LightMap map("deep shadow map", p, 4 * node_count);
  with_sampler(v.volume, [&](const auto& sampler) {
    map.fill([&](const Ray& ray, std::int64_t, float* texel) {
      deep_shadow_texel(v, sampler, ray, colors, tolerance, node_count, texel);
    });
    return 0;
  });
  return map;
}

// Largest depth change per texel, in texel footprints, that the
// slope-scaled bias follows (a surface about 83 degrees from facing the
// light); steeper changes are depth discontinuities.
inline constexpr float kDeepShadowMaxSlope = 8.0f;

// Visibility toward light `light`: the nodes of the nearest texel, or a
// bilinear blend of the four nearest texels' functions.
// Slope-scaled bias: on a surface inclined to the light a texel's ray
// enters it up to half a texel's depth change (a texel for bilinear)
// before or after the sample's own ray, and reading the texel's function at
// the sample's depth puts the sample that much too deep or too shallow in
// the material: moire stripes on grazing faces. Each texel is read at the
// sample's depth moved by slope_bias times the depth change of the
// occluder's entry (the first node, where the function leaves 1) between
// the sample and the texel's centre, from the gradient of the entries
// around the sample (LightMapView::plane_gradient): for slope_bias 1 the
// same depth below a planar occluder as the sample.
// With the PCSS filter on for the light (pcss.on(light), light_space/pcss.h)
// the blockers are the texels whose first node lies in front of the sample,
// and the filter averages the nearest-texel functions at the sample's depth
// (moved along the receiver plane as above) over the disk sized by them.
struct DeepShadowVisibility {
  const LightMapView* maps;
  // The device copy (backends/device.h).
  template <class Mirror> DeepShadowVisibility on_device(Mirror& m) const {
    DeepShadowVisibility d = *this;
    d.maps = light_maps_on_device(maps, m);
    return d;
  }
  int node_count;
  bool bilinear;
  float slope_bias = 1.0f;
  Pcss pcss{};  // no light on: `bilinear` or nearest

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

  // Texel (x, y) for point q, read at q's depth moved along the receiver
  // plane of gradient (gx, gy).
  template <class L>
  PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Vec3 plane_value(const LightMapView& map, const LightMapPointL<L>& q,
                                                                 typename L::Int x, typename L::Int y,
                                                                 typename L::Float gx, typename L::Float gy) const {
    const auto depth = q.depth + gx * (to_float(x) + 0.5f - q.x) + gy * (to_float(y) + 0.5f - q.y);
    return texel_value<L>(map, q.face, x, y, depth);
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
    F gx, gy;
    map.receiver_plane<L>(q, 0, kDeepShadowMaxSlope, slope_bias, gx, gy);
    if (pcss.on(light)) {
      typename L::Mask blocked;
      const F radius = pcss_radius<L>(pcss, light, map, q, 0, 0.0f, blocked);
      const auto shaded = seen & blocked;
      if (none(shaded)) return V(1.0f);
      const V value = pcss_filter<L, V>(pcss, q, radius,
                                        [&](const I& tx, const I& ty) { return plane_value<L>(map, q, tx, ty, gx, gy); });
      return select(shaded, value, V(1.0f));
    }
    if (!bilinear) {
      return select(seen, plane_value<L>(map, q, to_int(floor(q.x)), to_int(floor(q.y)), gx, gy), V(1.0f));
    }
    const F cx = q.x - 0.5f, cy = q.y - 0.5f;
    const F bx = floor(cx), by = floor(cy);
    const F fx = cx - bx, fy = cy - by;
    const I x = to_int(bx), y = to_int(by);
    const V v00 = plane_value<L>(map, q, x, y, gx, gy);
    const V v10 = plane_value<L>(map, q, x + I(1), y, gx, gy);
    const V v01 = plane_value<L>(map, q, x, y + I(1), gx, gy);
    const V v11 = plane_value<L>(map, q, x + I(1), y + I(1), gx, gy);
    const V top = v00 * (1.0f - fx) + v10 * fx;
    const V bottom = v01 * (1.0f - fx) + v11 * fx;
    return select(seen, top * (1.0f - fy) + bottom * fy, V(1.0f));
  }
};

PENUMBRA_PACKET_LIGHTING(ScatteringLighting<DeepShadowVisibility>);
PENUMBRA_DEVICE_LIGHTING(ScatteringLighting<DeepShadowVisibility>);

}  // namespace penumbra

#pragma once
// cssm kernels (Weidner & Linsen 2018, Tables 1 and 2).
//
// Generation (Table 1): a photon per texel and channel walks the light ray's
// segments; in segment i it is stopped with probability rho_i,lambda (the
// paper's alpha_i (1 - t_i,lambda), or penumbra's chromatic or grey model:
// light_ray.h), decided against one random threshold r_i per segment shared
// by the three channels; the texel keeps the first stopping depth per
// channel (+inf: never stopped) and the walk ends once all three are set
// and the entry depth (below) is found.
// penumbra stores, as that depth, a uniformly random point of the stopping
// segment (one more random number, shared by the channels stopping there)
// rather than a fixed point of it: then P(depth > z) is exactly the
// continuous piecewise-linear transmittance at z (light_ray.h), not a
// staircase with a step per segment.
//
// penumbra also stores a fourth value per texel, the ray's entry into the
// occluder: the depth where its least channel's transmittance falls to
// 1 - kCssmEntryOpacity, interpolated inside the segment (deterministic,
// not a photon's depth).
//
// Query (Table 2): the average over m offsets Delta_j (in texels of the
// map) of the per-channel tests "stored depth > lookup depth". Each test is
// an unbiased Bernoulli estimate of the transmittance of its texel's ray at
// that depth, so the expected visibility is the transmittance averaged over
// the texels read. With the paper's filter the lookup depth is the sample's
// for every tap. Then on a surface inclined to the light the taps stand for
// rays that enter it earlier or later than the sample's: self-shadowing
// blur on lit slopes, and on a face the light grazes the taps outside read
// rays that have not yet entered the occluder at the sample's depth: a
// leak. The depth-aware filter (default) fits a plane to the entry depths
// around the sample (LightMapView::depth_gradient of the entries), reads
// each tap at the sample's depth below that plane,
//   z_j = z + (entry_j - entry_at_sample),
// which is exact for any occluder that is a layer of constant profile, and
// rejects taps whose entry departs from the plane by more than
// kCssmMaxSlope texel footprints per texel of distance (another surface:
// across a silhouette, or an empty ray beside an occupied one). The
// rejections and shifts depend on the entries only, not on the photons, so
// the estimate stays unbiased for the shifted depths of the kept taps
// (cssm_test.cpp checks that against the brute-force transmittance).
#include "penumbra/render/lighting.h"
#include "penumbra/base/rng.h"
#include "penumbra/techniques/cssm/cssm_offsets.h"
#include "penumbra/techniques/light_space/light_map.h"
#include "penumbra/techniques/light_space/light_ray.h"
#include "penumbra/techniques/light_space/pcss.h"

namespace penumbra {

// The random stream of one texel of one light's map for a seed.
PENUMBRA_HD inline Pcg32 cssm_texel_rng(std::uint32_t seed, int light, std::int64_t texel) {
  const std::uint64_t key =
      mix_bits(mix_bits((std::uint64_t(seed) << 20) ^ std::uint64_t(light)) + std::uint64_t(texel));
  return Pcg32(key, mix_bits(key ^ 0x9e3779b97f4a7c15ULL));
}

// Opacity at which a light ray counts as having entered the occluder (the
// fourth value of a CSSM texel).
inline constexpr float kCssmEntryOpacity = 0.02f;
inline constexpr int kCssmValues = 4;  // r, g, b stopping depths and the entry
static_assert(kCssmValues == 4, "CssmVisibility reads a texel's values with one gather4");

// Per-channel stopping depths of one texel's photons (xyz) and the ray's
// entry depth (w).
template <class Sampler>
PENUMBRA_HD vec4 cssm_texel(const RenderView& v, const Sampler& sampler, const Ray& ray,
                            const ShadowColorModel& colors, Pcg32& rng) {
  vec3 depth(kInfinity);
  float entry = kInfinity;
  float transmittance = 1.0f;  // the least channel's
  const float target = 1.0f - kCssmEntryOpacity;
  march_light_ray(v, sampler, ray, kInfinity, [&](const LightSegment& s) {
    const float r = rng.next_float();
    const vec3 rho = stop_probability(s, colors);
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
    if (entry == kInfinity) {
      const float after = transmittance * (1.0f - max_component(rho));
      if (after <= target) {
        const float drop = transmittance - after;
        const float f = drop > 0.0f ? (transmittance - target) / drop : 0.0f;
        entry = s.start + glm::clamp(f, 0.0f, 1.0f) * s.length;
      }
      transmittance = after;
    }
    return open || entry == kInfinity;
  });
  return vec4(depth, entry);
}

// One CSSM for light number `light` with projection `p` (host).
inline LightMap build_cssm(const RenderView& v, const LightProjection& p, std::uint32_t seed, int light,
                           const ShadowColorModel& colors) {
  LightMap map("colored stochastic shadow map", p, kCssmValues);
  with_sampler(v.volume, [&](const auto& sampler) {
    map.fill([&](const Ray& ray, std::int64_t index, float* texel) {
      Pcg32 rng = cssm_texel_rng(seed, light, index);
      const vec4 values = cssm_texel(v, sampler, ray, colors, rng);
      for (int k = 0; k < kCssmValues; ++k) texel[k] = values[k];
    });
    return 0;
  });
  return map;
}

// Largest entry-depth change per texel, in texel footprints, that the
// depth-aware filter follows as one surface (about 83 degrees from facing
// the light).
inline constexpr float kCssmMaxSlope = 8.0f;

// Visibility toward light `light`: the fraction of the m offset tests that
// find the sample in front of the stored depth, per channel, over the taps
// kept. Offsets are in texels of the map: a finer map filters a smaller part
// of the light's view (resolution is a quality control).
struct CssmVisibility {
  const LightMapView* maps;
  // The device copy (backends/device.h).
  template <class Mirror> CssmVisibility on_device(Mirror& m) const {
    CssmVisibility d = *this;
    d.maps = light_maps_on_device(maps, m);
    return d;
  }
  vec2 offsets[kMaxCssmOffsets];  // texels of the map
  int offset_count;
  bool depth_aware = true;
  Pcss pcss{};  // no light on: the offsets

  // Offset j in texels of `map`.
  PENUMBRA_HD vec2 offset(const LightMapView& /*map*/, int j) const { return offsets[j]; }

  // Where the sample's entry plane lies (depth-aware filter).
  template <class L> struct Plane {
    typename L::Float entry;  // at the sample's texel coordinates
    typename L::Float cap;    // kCssmMaxSlope footprints per texel
  };

  template <class L>
  PENUMBRA_HD PENUMBRA_FORCE_INLINE Plane<L> entry_plane(const LightMapView& map, const LightMapPointL<L>& q) const {
    using F = typename L::Float;
    using I = typename L::Int;
    Plane<L> plane;
    plane.cap = kCssmMaxSlope * map.projection.texel_footprint(q.depth);
    const F cx = floor(q.x), cy = floor(q.y);
    const I x = to_int(cx), y = to_int(cy);
    typename L::Mask inside;
    const auto at = map.texel_offset<L>(q.face, x, y, inside);
    const F entry = select(inside, LightMapView::finite_depth(gather(map.texels, at + typename L::Index(3))),
                           F(LightMapView::kFarDepth));
    F gx, gy;
    map.depth_gradient<L>(q.face, x, y, 3, entry, plane.cap, gx, gy);
    plane.entry = entry + gx * (q.x - cx - 0.5f) + gy * (q.y - cy - 0.5f);
    return plane;
  }

  // Tap j: its texel's offset in the map, whether the map has it (else the
  // tap is lit), whether the filter keeps it, the depth to test and the
  // texel's three stopping depths (read with its entry in one gather4).
  template <class L> struct Tap {
    typename L::Index at;
    typename L::Mask inside, kept;
    typename L::Float depth;
    typename L::Float stop[3];
  };

  template <class L>
  PENUMBRA_HD PENUMBRA_FORCE_INLINE Tap<L> tap(const LightMapView& map, const LightMapPointL<L>& q,
                                               const Plane<L>& plane, int j) const {
    const vec2 o = offset(map, j);
    return tap_at<L>(map, q, plane, floor(q.x + o.x), floor(q.y + o.y), depth_aware);
  }

  // The tap of texel (tx, ty) (whole numbers), with the depth-aware filter
  // (`aware`) or the paper's.
  template <class L>
  PENUMBRA_HD PENUMBRA_FORCE_INLINE Tap<L> tap_at(const LightMapView& map, const LightMapPointL<L>& q,
                                                  const Plane<L>& plane, typename L::Float tx, typename L::Float ty,
                                                  bool aware) const {
    using F = typename L::Float;
    Tap<L> t;
    t.at = map.texel_offset<L>(q.face, to_int(tx), to_int(ty), t.inside);
    F stored_entry;
    gather4(map.texels, t.at, t.stop[0], t.stop[1], t.stop[2], stored_entry);
    t.depth = q.depth;
    t.kept = typename L::Mask(true);
    if (aware) {
      const F entry = select(t.inside, LightMapView::finite_depth(stored_entry), F(LightMapView::kFarDepth));
      const F ex = tx + 0.5f - q.x, ey = ty + 0.5f - q.y;
      const F distance = max(max(ex, -ex), max(ey, -ey));
      const F shift = entry - plane.entry;
      t.kept = max(shift, -shift) <= plane.cap * (distance + 1.0f);
      t.depth = q.depth + select(t.kept, shift, F(0.0f));
    }
    return t;
  }

  PENUMBRA_HD vec3 operator()(int light, vec3 p, const LightSample& ls) const {
    return lanes<ScalarLanes>(light, p, ls, true);
  }

  template <class L>
  PENUMBRA_HD typename L::Vec3 lanes(int light, const typename L::Vec3& p, const LightSampleL<L>& ls,
                                     typename L::Mask active) const {
    using F = typename L::Float;
    using V = typename L::Vec3;
    const LightMapView& map = maps[light];
    if constexpr (L::kWidth > 1) {
      if (!map.fits_packets()) return L::scalarize(*this, light, p, ls, active);
    }
    LightMapPointL<L> q;
    const auto seen = map.projection.locate<L>(p, q);
    if (none(seen)) return V(1.0f);
    Plane<L> plane{F(0.0f), F(0.0f)};
    if (depth_aware) plane = entry_plane<L>(map, q);
    V lit(0.0f);
    F kept(0.0f);
    const auto add = [&](const Tap<L>& t) {
      const auto in_front = [&](int channel) {
        return select(t.kept & ((!t.inside) | (t.stop[channel] > t.depth)), F(1.0f), F(0.0f));
      };
      lit += V(in_front(0), in_front(1), in_front(2));
      kept += select(t.kept, F(1.0f), F(0.0f));
    };
    auto shaded = seen;
    if (pcss.on(light)) {
      // The blockers: entries in front of the sample; the taps: the
      // filter disk's texels, each tested at the sample's depth (the paper's
      // test: the depth-aware filter would drop the taps beyond an
      // occluder's edge, the very taps that make the penumbra).
      typename L::Mask blocked;
      const F radius = pcss_radius<L>(pcss, light, map, q, 3, 0.0f, blocked);
      shaded = seen & blocked;
      if (none(shaded)) return V(1.0f);
      for (int j = 0; j < kPcssFilterTaps; ++j) {
        add(tap_at<L>(map, q, plane, floor(q.x + radius * pcss.filter[j].x), floor(q.y + radius * pcss.filter[j].y), false));
      }
    } else {
      for (int j = 0; j < offset_count; ++j) add(tap<L>(map, q, plane, j));
    }
    const auto any_kept = kept > 0.0f;
    return select(shaded & any_kept, lit / max(kept, F(1.0f)), V(1.0f));
  }
};

// The first `count` offsets of the paper's list, times `scale` (texels of
// the map), with the depth-aware filter or the paper's.
// `pcss`: the PCSS filter for the lights it has on (light_space/pcss.h).
inline CssmVisibility make_cssm_visibility(const LightMapView* maps, int count, float scale, bool depth_aware = true,
                                           const Pcss& pcss = Pcss{}) {
  CssmVisibility v{maps, {}, count, depth_aware, pcss};
  for (int j = 0; j < count; ++j) v.offsets[j] = scale * vec2(float(kCssmOffsets[j][0]), float(kCssmOffsets[j][1]));
  return v;
}

PENUMBRA_PACKET_LIGHTING(ScatteringLighting<CssmVisibility>);
PENUMBRA_DEVICE_LIGHTING(ScatteringLighting<CssmVisibility>);

}  // namespace penumbra

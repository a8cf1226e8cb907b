#pragma once
// Percentage-closer soft shadows (issue 18) for the light-map techniques
// (shadow-map, deep-shadow-map, cssm): a filter whose width follows the
// penumbra that the scene light's physical size casts, in place of each
// paper's fixed offsets. Per lit sample q (texel coordinates, depth d_r):
//
//   1. blocker search: kPcssSearchTaps taps on a disk around q whose radius
//      is where a blocker could still hide part of the light from q:
//        distant (half-angle theta)  d_r tan(theta) (depths start at a plane
//                                    in front of the volume)
//        sphere, disk (radius R)     R (d_r - R) / (d_r R) on the unit plane,
//                                    a blocker no nearer the light than R
//      both capped at kPcssMaxRadiusTexels texels. A tap whose occluder depth
//      (shadow-map: the stored depth; deep-shadow-map: the first node;
//      cssm: the entry) lies in front of d_r - bias is a blocker; none: lit.
//   2. the mean blocker depth d_b and, by similar triangles, the half-width
//      of the penumbra at q:
//        distant       w = (d_r - d_b) tan(theta)
//        sphere, disk  w = R (d_r - d_b) / d_b
//      in texels of q's depth (w / texel_footprint(d_r)), capped as above.
//   3. the filter: kPcssFilterTaps taps on the disk of radius w (a fixed
//      golden-angle spiral, the same for every sample: deterministic), each
//      the technique's own test at its texel (a depth test, the deep shadow
//      function at the sample's depth, the stochastic tests), averaged.
//
// A disk-shaped filter of radius w under a planar occluder averages exactly
// what a uniform disk light of that angular radius sees: behind a straight
// edge the circular-segment profile, 10-90 % width 1.3741 w, of the full
// penumbra 2 w = 2 (d_r - d_b) tan(theta) (tests/.../shadow_maps_pcss_test.cpp).
// A gaussian distant light counts as the uniform disk of the same variance,
// tan(theta) = 2 tan(sigma) (as cone-shadows); a light without a size
// (directional, point, radius 0) gets the paper's filter unchanged.
#include "penumbra/base/lanes.h"
#include "penumbra/scene/light.h"
#include "penumbra/techniques/light_space/light_map.h"

#include <cmath>
#include <cstdint>
#include <vector>

namespace penumbra {

inline constexpr int kPcssLights = 8;  // lights beyond the 8th keep the paper's filter
inline constexpr int kPcssSearchTaps = 16;
inline constexpr int kPcssFilterTaps = 48;
inline constexpr float kPcssMaxRadiusTexels = 96.0f;

enum class PcssSize : std::uint8_t { None, Angular, Radius };

struct PcssLight {
  PcssSize kind = PcssSize::None;
  float size = 0.0f;  // Angular: tan of the half-angle; Radius: world radius
};

struct Pcss {
  PcssLight lights[kPcssLights];
  vec2 search[kPcssSearchTaps];  // unit disk
  vec2 filter[kPcssFilterTaps];  // unit disk

  PENUMBRA_HD bool on(int light) const { return light < kPcssLights && lights[light].kind != PcssSize::None; }
};

// The size of `light` as the filter reads it (None: no size).
inline PcssLight pcss_light(const Light& l) {
  PcssLight p;
  if (l.type == LightType::Distant && l.angle_deg > 0.0f) {
    const float x = std::tan(glm::radians(glm::min(l.angle_deg, 89.0f)));
    const float y = std::tan(glm::radians(glm::min(l.spread_y_deg(), 89.0f)));
    p.kind = PcssSize::Angular;
    p.size = l.profile == LightProfile::Uniform ? x : 2.0f * std::sqrt(0.5f * (x * x + y * y));
  } else if ((l.type == LightType::Sphere || l.type == LightType::Disk) && l.radius > 0.0f) {
    p.kind = PcssSize::Radius;
    p.size = l.radius;
  }
  return p;
}

// Whether any of `lights` has a size the filter follows.
inline bool any_pcss_light(const std::vector<Light>& lights) {
  for (std::size_t i = 0; i < lights.size() && i < std::size_t(kPcssLights); ++i) {
    if (pcss_light(lights[i]).kind != PcssSize::None) return true;
  }
  return false;
}

// `count` points of a golden-angle spiral filling the unit disk with equal
// area per point (radius sqrt((j + 1/2) / count)).
inline void pcss_spiral(vec2* out, int count) {
  const double golden = 3.14159265358979323846 * (3.0 - std::sqrt(5.0));
  for (int j = 0; j < count; ++j) {
    const double r = std::sqrt((double(j) + 0.5) / double(count));
    out[j] = vec2(float(r * std::cos(golden * j)), float(r * std::sin(golden * j)));
  }
}

// The filter for `lights` (enabled false: every light keeps the paper's).
inline Pcss make_pcss(const std::vector<Light>& lights, bool enabled) {
  Pcss p;
  if (enabled) {
    for (std::size_t i = 0; i < lights.size() && i < std::size_t(kPcssLights); ++i) p.lights[i] = pcss_light(lights[i]);
  }
  pcss_spiral(p.search, kPcssSearchTaps);
  pcss_spiral(p.filter, kPcssFilterTaps);
  return p;
}

// Steps 1 and 2 above for point q under light `light` (p.on(light)): the
// filter radius in texels, and in `blocked` the lanes with a blocker (the
// others are lit). `index` is the occluder depth's value in a texel; a
// blocker lies in front of q.depth - bias.
template <class L>
PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Float pcss_radius(const Pcss& p, int light, const LightMapView& map,
                                                                const LightMapPointL<L>& q, int index, float bias,
                                                                typename L::Mask& blocked) {
  using F = typename L::Float;
  using M = typename L::Mask;
  const PcssLight& size = p.lights[light];
  const F footprint = map.projection.texel_footprint(q.depth);
  const F cap(kPcssMaxRadiusTexels);
  F search;
  if (size.kind == PcssSize::Angular) {
    search = max(q.depth, F(0.0f)) * size.size / footprint;
  } else {
    const float per_texel = 2.0f * map.projection.window_half / float(map.projection.resolution);
    search = size.size * max(q.depth - size.size, F(0.0f)) / (max(q.depth, F(1e-6f)) * (size.size * per_texel));
  }
  search = min(search, cap);
  F sum(0.0f), count(0.0f);
  for (int j = 0; j < kPcssSearchTaps; ++j) {
    M inside;
    const auto at =
        map.texel_offset<L>(q.face, to_int(floor(q.x + search * p.search[j].x)),
                            to_int(floor(q.y + search * p.search[j].y)), inside);
    const F stored = select(inside, LightMapView::finite_depth(gather(map.texels, at + typename L::Index(index))),
                            F(LightMapView::kFarDepth));
    const M blocker = inside & (stored < q.depth - bias);
    sum += select(blocker, stored, F(0.0f));
    count += select(blocker, F(1.0f), F(0.0f));
  }
  blocked = count > 0.0f;
  const F blocker_depth = sum / max(count, F(1.0f));
  const F gap = max(q.depth - blocker_depth, F(0.0f));
  F width;
  if (size.kind == PcssSize::Angular) {
    width = gap * size.size;
  } else {
    width = size.size * gap / max(blocker_depth, F(1e-6f));
  }
  return min(width / footprint, cap);
}

// Step 3: the mean of tap(tx, ty) over the filter disk of `radius` texels
// around q.
template <class L, class R, class Tap>
PENUMBRA_HD PENUMBRA_FORCE_INLINE R pcss_filter(const Pcss& p, const LightMapPointL<L>& q,
                                                typename L::Float radius, const Tap& tap) {
  R sum(0.0f);
  for (int j = 0; j < kPcssFilterTaps; ++j) {
    sum += tap(to_int(floor(q.x + radius * p.filter[j].x)), to_int(floor(q.y + radius * p.filter[j].y)));
  }
  return sum * (1.0f / float(kPcssFilterTaps));
}

}  // namespace penumbra

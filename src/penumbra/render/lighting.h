#pragma once
// How a sample or a plane hit is lit (DESIGN.md 1):
//   phase:  albedo * c * (ambient + sum_l p(cos) * L_l * V_l)
//   phong:  albedo * c * (ambient + sum_l kd max(0, n.l) L_l V_l) + sum_l ks (n.h)^s L_l V_l
//   plane:  colour * (ambient + sum_l max(0, n.l) L_l V_l)
// Every technique shares this code; each supplies only the light visibility
// V_l(x) through a Visibility functor:
//   vec3 operator()(int light, vec3 position, const LightSample&) const
// returning the volume's transmittance toward that light per colour channel,
// in [0, 1] (grey for the physical model; techniques with coloured shadows
// such as CSSM return colours). Opaque planes between a point and a light
// block it for every technique.
//
// Samples are lit for one ray or a packet of rays (base/lanes.h). A
// Visibility may also provide the packet form, written once over the lane
// type (its operator() then being the one-lane instance):
//   template <class L> L::Vec3 lanes(int light, const L::Vec3& position,
//                                    const LightSampleL<L>&, L::Mask active) const
// Without it, packets call operator() lane by lane (L::scalarize).
#include "penumbra/backends/cpu/packets.h"
#include "penumbra/backends/device.h"
#include "penumbra/base/lanes.h"
#include "penumbra/render/march.h"
#include "penumbra/scene/light.h"
#include "penumbra/scene/material.h"
#include "penumbra/volume/volume_sampler.h"

namespace penumbra {

// Lanes where an opaque plane (other than `skip`) lies between p and the light.
template <class L>
PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Mask blocked_by_planes(const RenderView& v, const typename L::Vec3& p,
                                                                     const LightSampleL<L>& ls, int skip = -1) {
  using F = typename L::Float;
  using V = typename L::Vec3;
  typename L::Mask blocked(false);
  for (int i = 0; i < v.plane_count; ++i) {
    if (i == skip) continue;
    const V normal(v.planes[i].normal);
    const F denom = dot(ls.to_light, normal);
    const F t = dot(V(v.planes[i].point) - p, normal) / denom;
    blocked = blocked | ((denom != 0.0f) & (t > 0.0f) & (t < ls.distance));
  }
  return blocked;
}

PENUMBRA_HD inline bool blocked_by_planes(const RenderView& v, vec3 p, const LightSample& ls, int skip = -1) {
  return blocked_by_planes<ScalarLanes>(v, p, ls, skip);
}

// Unit shading normal from the gradient (precomputed normals when the view
// has them), facing the viewer; false in lanes where the gradient vanishes
// (homogeneous regions), which are then lit as if facing the light without a
// highlight.
template <class L>
PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Mask shading_normal(const RenderView& v, const SamplePointL<L>& s,
                                                                  typename L::Vec3& normal) {
  using F = typename L::Float;
  using V = typename L::Vec3;
  const V g = v.normals.texels
                  ? (s.cell ? v.normals.sample_at<L>(*s.cell) : v.normals.sample<L>(s.index))
                  : AnyVoxelSampler(v.volume.data, v.volume.dims, v.volume.type).gradient<L>(s.index) /
                        V(v.volume.spacing);
  const F len = length(g);
  const auto ok = (len > 0.0f) & finite(len);
  if (none(ok)) return ok;
  normal = -g / len;  // from high to low values: outward for a bright object
  normal = select(dot(normal, s.ray_dir) > 0.0f, -normal, normal);
  return ok;
}

PENUMBRA_HD inline bool shading_normal(const RenderView& v, const SamplePoint& s, vec3& normal) {
  return shading_normal<ScalarLanes>(v, s, normal);
}

// The visibility of light `light` at packet or single positions (see above).
template <class L, class Visibility>
PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Vec3 light_visibility(const Visibility& visibility, int light,
                                                                    const typename L::Vec3& p,
                                                                    const LightSampleL<L>& ls, typename L::Mask active) {
  if constexpr (L::kWidth == 1) {
    return visibility(light, p, ls);
  } else if constexpr (requires { visibility.template lanes<L>(light, p, ls, active); }) {
    return visibility.template lanes<L>(light, p, ls, active);
  } else {
    return L::scalarize(visibility, light, p, ls, active);
  }
}

// Trilinear lookups of a grid at world positions (VolumeView::sample for
// lanes): the shadow caches of shadow-rays, filtered-sat, sat-ao and
// cone-shadows.
template <class L>
PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Float sample_world(const VolumeView& grid, const typename L::Vec3& p) {
  return AnyVoxelSampler(grid.data, grid.dims, grid.type).sample<L>(grid.index_from_world<L>(p));
}

// The visibility of light `light` at p on opaque plane `plane`: the
// functor's own plane lookup where it has one (a shadow cache on the plane,
// sat_common/plane_caches.h), its visibility at p otherwise.
template <class Visibility>
PENUMBRA_HD PENUMBRA_FORCE_INLINE vec3 plane_visibility(const Visibility& visibility, int light, int plane, vec3 p,
                                                        const LightSample& ls) {
  if constexpr (requires { visibility.plane(light, plane, p, ls); }) {
    return visibility.plane(light, plane, p, ls);
  } else {
    return visibility(light, p, ls);
  }
}

// A cached visibility: the cache grid inside `box` (where the volume's
// samples lie), the technique's direct lookup `direct` elsewhere (plane hits);
// no cache (data == nullptr): always direct.
template <class L, class Direct>
PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Vec3 cached_visibility(const VolumeView& cache, const Box3& box,
                                                                     const Direct& direct, int light,
                                                                     const typename L::Vec3& p,
                                                                     const LightSampleL<L>& ls,
                                                                     typename L::Mask active) {
  using V = typename L::Vec3;
  if constexpr (L::kWidth == 1) {
    if (cache.data && box.contains(p)) return V(cache.sample(p));
    return direct(light, p, ls);
  } else {
    if (!cache.data) return light_visibility<L>(direct, light, p, ls, active);
    const auto inside = box_contains<L>(box, p);
    V result(sample_world<L>(cache, p));
    const auto outside = active & !inside;
    if (any(outside)) result = select(outside, light_visibility<L>(direct, light, p, ls, outside), result);
    return result;
  }
}

// A cached transmittance along the light ray (the shadow-ray cache: a texel
// holds the transmittance from the texel toward the light's centre). Outside
// the box there is no medium, so a point there (a plane hit) sees what the
// cache holds where its shadow ray enters the box, and 1 where the ray misses
// it: one lookup instead of a shadow ray through the volume. No cache
// (data == nullptr): always direct.
template <class L, class Direct>
PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Vec3 entry_cached_visibility(const VolumeView& cache, const Box3& box,
                                                                           const Direct& direct, int light,
                                                                           const typename L::Vec3& p,
                                                                           const LightSampleL<L>& ls,
                                                                           typename L::Mask active) {
  using F = typename L::Float;
  using V = typename L::Vec3;
  if (!cache.data) return light_visibility<L>(direct, light, p, ls, active);
  const auto inside = box_contains<L>(box, p);
  if constexpr (L::kWidth == 1) {
    if (inside) return V(cache.sample(p));
  } else {
    if (all(inside | !active)) return V(sample_world<L>(cache, p));
  }
  F t_entry(0.0f);
  F t_exit = ls.distance;
  box_overlap<L>(box, p, ls.to_light, t_entry, t_exit);
  const auto hit = t_entry <= t_exit;
  const V q = select(inside, p, p + ls.to_light * t_entry);
  return V(select(inside | hit, sample_world<L>(cache, q), F(1.0f)));
}

struct NoShadows {
  template <class Mirror> NoShadows on_device(Mirror&) const { return *this; }
  PENUMBRA_HD vec3 operator()(int, vec3, const LightSample&) const { return vec3(1.0f); }
  template <class L>
  PENUMBRA_HD typename L::Vec3 lanes(int, const typename L::Vec3&, const LightSampleL<L>&, typename L::Mask) const {
    return typename L::Vec3(1.0f);
  }
};

template <class Visibility>
struct ScatteringLighting {
  const RenderView* view;
  Visibility visibility;
  Shading shading;

  // The device copy (backends/device.h): the view and the visibility's
  // structures mirrored.
  template <class Mirror> ScatteringLighting on_device(Mirror& m) const {
    return ScatteringLighting{m.view(*view), visibility.on_device(m), shading};
  }

  template <class L>
  PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Vec3 sample(const SamplePointL<L>& s, typename L::Mask active) const {
    using F = typename L::Float;
    using V = typename L::Vec3;
    using M = typename L::Mask;
    const RenderView& v = *view;
    const Material& m = v.material;
    const V albedo = m.albedo * s.color;
    V normal(0.0f);
    const bool phong = shading == Shading::Phong;
    M has_normal(false);
    if (phong) has_normal = shading_normal<L>(v, s, normal) & active;
    V diffuse(m.ambient);
    V specular(0.0f);
    for (int i = 0; i < v.light_count; ++i) {
      const LightSampleL<L> ls = sample_light<L>(v.lights[i], s.world);
      F factor;
      if (!phong) {
        factor = phase_hg_4pi(m.phase_g, dot(ls.to_light, s.ray_dir));
      } else {
        factor = select(has_normal, m.diffuse * max(F(0.0f), dot(normal, ls.to_light)), F(m.diffuse));
      }
      F highlight(0.0f);
      if (m.specular > 0.0f && any(has_normal)) {
        highlight = select(
            has_normal,
            m.specular * pow_unit(max(F(0.0f), dot(normal, normalize(ls.to_light - s.ray_dir))), m.shininess),
            F(0.0f));
      }
      M lit = active & ((factor > 0.0f) | (highlight > 0.0f));
      if (none(lit)) continue;
      if (v.plane_count > 0) {
        lit = lit & !blocked_by_planes<L>(v, s.world, ls);
        if (none(lit)) continue;
      }
      const V visible = light_visibility<L>(visibility, i, s.world, ls, lit) * ls.radiance;
      diffuse += select(lit, factor * visible, V(0.0f));
      specular += select(lit, highlight * visible, V(0.0f));
    }
    return albedo * diffuse + specular;
  }

  PENUMBRA_HD PENUMBRA_FORCE_INLINE vec3 sample(const SamplePoint& s) const { return sample<ScalarLanes>(s, true); }

  PENUMBRA_HD vec3 plane(const PlaneHit& h) const {
    const RenderView& v = *view;
    const Plane& p = v.planes[h.plane];
    // The side of the plane the viewer sees.
    const vec3 normal = glm::dot(p.normal, h.ray_dir) < 0.0f ? p.normal : -p.normal;
    vec3 sum(v.material.ambient);
    for (int i = 0; i < v.light_count; ++i) {
      const LightSample ls = sample_light(v.lights[i], h.position);
      const float cosine = glm::dot(normal, ls.to_light);
      if (cosine <= 0.0f) continue;
      if (blocked_by_planes(v, h.position, ls, h.plane)) continue;
      sum += cosine * plane_visibility(visibility, i, h.plane, h.position, ls) * ls.radiance;
    }
    return p.color * sum;
  }
};

// Unlit emission-absorption: the TF colour is the emitted radiance; planes
// show their colour.
struct EmissionLighting {
  const RenderView* view;
  template <class Mirror> EmissionLighting on_device(Mirror& m) const { return EmissionLighting{m.view(*view)}; }
  template <class L>
  PENUMBRA_HD typename L::Vec3 sample(const SamplePointL<L>& s, typename L::Mask) const {
    return s.color;
  }
  PENUMBRA_HD vec3 sample(const SamplePoint& s) const { return s.color; }
  PENUMBRA_HD vec3 plane(const PlaneHit& h) const { return view->planes[h.plane].color; }
};

PENUMBRA_PACKET_LIGHTING(EmissionLighting);
PENUMBRA_PACKET_LIGHTING(ScatteringLighting<NoShadows>);
PENUMBRA_DEVICE_LIGHTING(EmissionLighting);
PENUMBRA_DEVICE_LIGHTING(ScatteringLighting<NoShadows>);

}  // namespace penumbra

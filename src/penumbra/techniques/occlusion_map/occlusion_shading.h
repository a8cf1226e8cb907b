#pragma once
// How occlusion-map points are lit. The shared ScatteringLighting does the
// Blinn-Phong (or phase) shading and the planes; the occlusion map supplies
// the light visibility (hard or soft shadows, optionally times the ambient
// occlusion: the paper's figures darken the direct light by it too) and scales
// the ambient term by the ambient occlusion (the scene's `ambient` stands for
// the uniform sky light that ambient occlusion is about). The lighting
// therefore runs on a view whose material has ambient 0, and the occluded
// ambient is added here.
#include "penumbra/render/lighting.h"
#include "penumbra/techniques/occlusion_map/isosurface_ray.h"
#include "penumbra/techniques/occlusion_map/occlusion_queries.h"
#include "penumbra/techniques/occlusion_map/soft_shadow_batch.h"
#include "penumbra/techniques/sat_common/plane_caches.h"

namespace penumbra {

enum class ShadowMode : std::uint8_t { None, Hard, Soft };

// Normalises data values the way the pyramid was built (u in [0, 1]).
struct ValueNormalisation {
  float lo = 0.0f;
  float scale = 1.0f;
  template <class F> PENUMBRA_HD F operator()(F value) const { return (value - lo) * scale; }
};

// Everything the per-point shading reads, shared by every pixel.
template <int K> struct OcclusionShadingSetup {
  const RenderView* lit_view = nullptr;  // the scene's view with ambient 0
  const RenderView* iso_view = nullptr;  // IsoOccupancy view, for iso rays and hard shadows
  OcclusionQueries<K> queries;
  ValueNormalisation normalise;
  float iso = 0.0f;      // data units
  vec3 iso_color{1.0f};  // TF colour at the iso-value
  float ambient = 0.0f;  // the scene's ambient term
  ShadowMode shadows = ShadowMode::Soft;
  bool ambient_occlusion = true;
  bool ao_on_lights = true;
  // Soft shadows on the opaque planes, per light and plane where the volume
  // can shadow them (occlusion_map.cpp); lights without a grid march.
  PlaneCachesView plane_shadows;

  // The device copy (backends/device.h): the views and the pyramid mirrored,
  // the setup itself copied for this frame. The iso view's occupancy follows
  // the iso-value, a parameter no scene version counts, so it is copied
  // every frame (a few bytes per macrocell).
  template <class Mirror> const OcclusionShadingSetup* on_device(Mirror& m) const {
    OcclusionShadingSetup d = *this;
    d.lit_view = m.view(*lit_view);
    d.iso_view = m.view(*iso_view, Mirror::Cells::PerFrame);
    d.queries.pyramid = queries.pyramid.on_device(m);
    d.plane_shadows = plane_shadows.on_device(m);
    return m.frame(&d, 1, "the occlusion shading setup");
  }
};

// Per-light visibility of one surface or plane point.
template <int K, class Sampler> struct SurfaceVisibility {
  const OcclusionShadingSetup<K>* setup;
  Sampler sampler;
  vec3 normal;        // unit, pointing away from the occluding side
  float query;        // normalised occlusion query value t (ambient occlusion)
  float own_value;    // normalised value under the surface (negative: a plane, no volume under it)
  float ambient_occ;  // multiplies every light (1 when AO darkens only the ambient term)
  // Soft shadows on CPU packets (soft_shadow_batch.h): the march toward
  // light deferred->light is recorded, not run, and the other lights are dark.
  SoftShadowQueries* deferred = nullptr;

  PENUMBRA_HD vec3 operator()(int light, vec3 p, const LightSample& ls) const {
    const OcclusionShadingSetup<K>& s = *setup;
    if (deferred && light != deferred->light) return vec3(0.0f);
    float visible = ambient_occ;
    if (s.shadows == ShadowMode::Hard) {
      // One voxel off the surface, so the ray does not find the surface it leaves.
      const vec3 start = p + normal * s.iso_view->volume.min_spacing();
      if (iso_blocks(*s.iso_view, sampler, Ray{start, ls.to_light}, ls.distance, s.iso)) return vec3(0.0f);
    } else if (s.shadows == ShadowMode::Soft) {
      const float spread = s.queries.light_spread(s.iso_view->lights[light], p);
      if (deferred) {
        deferred->record(p, normal, ls.to_light, ls.distance, spread, own_value);
        return vec3(visible);
      }
      // Every occluder above the iso-value blocks the light, also one less
      // dense than the material under this surface.
      visible *= s.queries.soft_shadow(p, normal, ls.to_light, ls.distance, spread, s.normalise(s.iso), own_value);
    }
    return vec3(visible);
  }
  // A point on opaque plane `plane` (this visibility's normal is the plane's,
  // its own value negative): the plane's soft-shadow grid where it has one.
  PENUMBRA_HD vec3 plane(int light, int plane, vec3 p, const LightSample& ls) const {
    const OcclusionShadingSetup<K>& s = *setup;
    if (s.shadows != ShadowMode::Soft || !s.plane_shadows.has(light, plane)) return (*this)(light, p, ls);
    if (deferred && light != deferred->light) return vec3(0.0f);
    return vec3(ambient_occ * s.plane_shadows.sample(light, plane, p));
  }
};

struct UniformVisibility {
  float value = 1.0f;
  PENUMBRA_HD vec3 operator()(int, vec3, const LightSample&) const { return vec3(value); }
  template <class L>
  PENUMBRA_HD typename L::Vec3 lanes(int, const typename L::Vec3&, const LightSampleL<L>&, typename L::Mask) const {
    return typename L::Vec3(value);
  }
};

// Shading of isosurface hits and plane hits (isosurface mode).
template <int K, class Sampler> struct IsosurfaceShader {
  const OcclusionShadingSetup<K>* setup;
  Sampler sampler;

  // Outward unit normal at a surface point from the central-difference
  // gradient (toward lower values), facing the viewer.
  PENUMBRA_HD vec3 surface_normal(vec3 index, vec3 ray_dir) const {
    const VolumeView& volume = setup->iso_view->volume;
    const vec3 g = sampler.gradient(index) / volume.spacing;
    const float length = glm::length(g);
    vec3 n = length > 0.0f && is_finite(length) ? -g / length : -ray_dir;
    if (glm::dot(n, ray_dir) > 0.0f) n = -n;
    return n;
  }

  // `deferred`: soft shadows deferred to packets (soft_shadow_batch.h); the
  // result is then the ambient term and the shares of lights that recorded no
  // march (none, or a plane's shadow grid); the others' shares are recorded.
  PENUMBRA_HD vec3 surface(vec3 p, vec3 ray_dir, SoftShadowQueries* deferred = nullptr) const {
    const OcclusionShadingSetup<K>& s = *setup;
    const VolumeView& volume = s.iso_view->volume;
    const vec3 index = volume.index_from_world(p);
    const vec3 n = surface_normal(index, ray_dir);
    // The query value: half a voxel under the surface (Fig. 7), at least the iso-value.
    const float under = sampler(volume.index_from_world(p - n * (0.5f * volume.min_spacing())));
    const float query = s.normalise(glm::max(s.iso, is_finite(under) ? under : s.iso));
    const float ao = s.ambient_occlusion ? s.queries.ambient(p, n, query) : 1.0f;
    using Visibility = SurfaceVisibility<K, Sampler>;
    const ScatteringLighting<Visibility> lighting{
        s.lit_view, Visibility{setup, sampler, n, query, query, s.ao_on_lights ? ao : 1.0f, deferred}, Shading::Phong};
    const SamplePoint sample{p, index, s.iso, s.iso_color, 0.0f, ray_dir};
    const vec3 ambient = s.lit_view->material.albedo * s.iso_color * (s.ambient * ao);
    if (!deferred) return lighting.sample(sample) + ambient;
    return ambient + deferred->defer_lights(s.lit_view->light_count, [&] { return lighting.sample(sample); });
  }

  PENUMBRA_HD vec3 plane(const PlaneHit& h, SoftShadowQueries* deferred = nullptr) const {
    const OcclusionShadingSetup<K>& s = *setup;
    const Plane& plane = s.lit_view->planes[h.plane];
    const vec3 facing = glm::normalize(glm::dot(plane.normal, h.ray_dir) < 0.0f ? plane.normal : -plane.normal);
    const float query = s.normalise(s.iso);
    const float ao = s.ambient_occlusion ? s.queries.ambient(h.position, facing, query) : 1.0f;
    using Visibility = SurfaceVisibility<K, Sampler>;
    const ScatteringLighting<Visibility> lighting{
        s.lit_view, Visibility{setup, sampler, facing, query, -1.0f, s.ao_on_lights ? ao : 1.0f, deferred},
        Shading::Phong};
    const vec3 ambient = plane.color * (s.ambient * ao);
    if (!deferred) return lighting.plane(h) + ambient;
    return ambient + deferred->defer_lights(s.lit_view->light_count, [&] { return lighting.plane(h); });
  }
};

// What a DVR sample receives light on, as DVR mode reads the occlusion map:
// the unit normal away from the denser side (the negated gradient) and the
// value under it (`depth` voxels back along the normal, half a voxel for a
// sample, or the sample's own where that is larger). Not oriented in
// homogeneous regions (nor in lanes that are off). For one lane or a packet.
template <class L> struct DvrReceiverL {
  typename L::Vec3 normal{0.0f};
  typename L::Float value{0.0f};  // data units
  typename L::Mask oriented{false};
};
using DvrReceiver = DvrReceiverL<ScalarLanes>;
template <class L, class Sampler>
PENUMBRA_HD PENUMBRA_FORCE_INLINE DvrReceiverL<L> dvr_receiver(const VolumeView& volume, const Sampler& sampler,
                                                               const typename L::Vec3& index,
                                                               const typename L::Vec3& world, typename L::Float value,
                                                               typename L::Mask active, float depth = 0.5f) {
  using V = typename L::Vec3;
  DvrReceiverL<L> r;
  r.value = value;
  const V g = sampler.template gradient<L>(index) / V(volume.spacing);
  const typename L::Float len = length(g);
  r.oriented = active & (len > 0.0f) & finite(len);
  if (none(r.oriented)) return r;
  r.normal = select(r.oriented, -g / len, V(0.0f));
  const V under_at = volume.index_from_world<L>(world - r.normal * (depth * volume.min_spacing()));
  const typename L::Float under = sampler.template sample<L>(under_at);
  r.value = select(r.oriented & finite(under), max(value, under), value);
  return r;
}
template <class Sampler>
PENUMBRA_HD DvrReceiver dvr_receiver(const VolumeView& volume, const Sampler& sampler, vec3 index, vec3 world,
                                     float value) {
  return dvr_receiver<ScalarLanes>(volume, sampler, index, world, value, true);
}

// Where dvr_ambient is taken: at a DVR sample (the paper's Fig. 11), or at a
// node of the AO grid (occlusion_map.cpp), which stands for the samples
// within a voxel of it. Samples that show lie in a surface's ramp, above the
// value of the air beside it; a node in that air queried with its own value
// came out darker than they (balls over a slab: rmse 2.7e-2 grid against per
// sample at half a voxel, 6.9e-3 at one voxel; dvr_shadows_test.cpp), so a
// node's receiver value is taken one voxel under it.
struct DvrAmbientAt {
  float under_depth = 0.5f;  // voxels under the point of the receiver's value
  float unoriented = 1.0f;   // the AO where the data is homogeneous
};
inline constexpr DvrAmbientAt kDvrSample{0.5f, 1.0f};
// The grid marks homogeneous nodes with -1 and fills them from their neighbours.
inline constexpr DvrAmbientAt kDvrGridNode{1.0f, -1.0f};

// DVR mode's ambient occlusion at a point of the volume (index and world
// position, the data value there): the four-level query from the receiver
// above, at.unoriented where the data is homogeneous (no direction to look
// in) and 1 on lanes that are off. The same per sample (dvr_ao=sample) and
// per node of the AO grid (dvr_ao=grid), for one lane or a packet.
template <class L, int K, class Sampler>
PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Float dvr_ambient(const OcclusionQueries<K>& queries,
                                                                ValueNormalisation normalise, const VolumeView& volume,
                                                                const Sampler& sampler, const typename L::Vec3& index,
                                                                const typename L::Vec3& world, typename L::Float value,
                                                                typename L::Mask active, DvrAmbientAt at = kDvrSample) {
  using F = typename L::Float;
  const DvrReceiverL<L> r = dvr_receiver<L>(volume, sampler, index, world, value, active, at.under_depth);
  const F homogeneous = select(active, F(at.unoriented), F(1.0f));
  if (none(r.oriented)) return homogeneous;
  const F ao = queries.template ambient_lanes<L>(world, r.normal, normalise(r.value), r.oriented);
  return select(r.oriented, ao, homogeneous);
}

// dvr_ambient at `count` AO grid nodes (world x, y, z arrays, padded to 16;
// kDvrGridNode) as SIMD packets of Target, two moments
// (occlusion_map_packets.cpp).
template <SimdTarget Target>
void dvr_ambient_batch(const OcclusionQueries<2>& queries, ValueNormalisation normalise, const VolumeView& volume,
                       const float* const xyz[3], int count, float* out);
using DvrAmbientBatch = void (*)(const OcclusionQueries<2>&, ValueNormalisation, const VolumeView&,
                                 const float* const[3], int, float*);

// DVR mode's soft shadow at a world point p toward `light`: the iso mode's
// march (OcclusionQueries::soft_shadow, every occluder above the iso-value)
// from a receiver oriented as above (its half-space taken out, the march
// lifted off it), or, where the data is homogeneous, lifted toward the light
// with nothing taken out. The march's arguments, for one lane or a batch
// (occlusion_map.cpp evaluates it once per node of each light's grid).
struct SoftShadowQuery {
  vec3 p, n, to_light;
  float distance, spread, own;
};
template <int K, class Sampler>
PENUMBRA_HD SoftShadowQuery dvr_soft_shadow_query(const OcclusionQueries<K>& queries, const VolumeView& volume,
                                                  const Sampler& sampler, ValueNormalisation normalise,
                                                  const Light& light, vec3 p) {
  const LightSample ls = sample_light(light, p);
  SoftShadowQuery q{p, ls.to_light, ls.to_light, ls.distance, queries.light_spread(light, p), -1.0f};
  const vec3 index = volume.index_from_world(p);
  const DvrReceiver r = dvr_receiver(volume, sampler, index, p, sampler(index));
  if (r.oriented) {
    q.n = r.normal;
    q.own = normalise(r.value);
  }
  return q;
}
// The soft shadow at a node of a plane's grid (occlusion_map.cpp): the plane
// seen from the light's side (the side a lit pixel shows), nothing of the
// volume under it; what SurfaceVisibility marches from a plane point.
template <int K>
PENUMBRA_HD SoftShadowQuery plane_soft_shadow_query(const OcclusionQueries<K>& queries, const Light& light,
                                                    const Plane& plane, vec3 p) {
  const LightSample ls = sample_light(light, p);
  const vec3 n = glm::normalize(glm::dot(plane.normal, ls.to_light) >= 0.0f ? plane.normal : -plane.normal);
  return SoftShadowQuery{p, n, ls.to_light, ls.distance, queries.light_spread(light, p), -1.0f};
}
template <int K>
PENUMBRA_HD float soft_shadow(const OcclusionQueries<K>& queries, const SoftShadowQuery& q, float t) {
  return queries.soft_shadow(q.p, q.n, q.to_light, q.distance, q.spread, t, q.own);
}

// A DVR sample's light visibility: inside the volume's box, the light's
// soft-shadow grid (lighting.h's cached_visibility; unshadowed without a
// grid). The ambient occlusion multiplies the lit result (DvrOcclusionLighting).
struct DvrVisibility {
  const VolumeView* grids = nullptr;  // per light; null, or data == nullptr: unshadowed
  Box3 box;
  PENUMBRA_HD vec3 operator()(int light, vec3 p, const LightSample& ls) const {
    return lanes<ScalarLanes>(light, p, ls, true);
  }
  template <class L>
  PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Vec3 lanes(int light, const typename L::Vec3& p,
                                                           const LightSampleL<L>& ls, typename L::Mask active) const {
    if (!grids) return typename L::Vec3(1.0f);
    return cached_visibility<L>(grids[light], box, UniformVisibility{1.0f}, light, p, ls, active);
  }
};

// DVR mode (Fig. 11): the same ambient occlusion for every DVR sample, with
// the value under it as the query (dvr_ambient: half a voxel at a sample, one
// at a grid node), either evaluated per sample or read trilinearly from a
// grid of it (`ambient_grid` times `ambient_scale`; data == nullptr: per
// sample), and with soft shadows from each light's grid (none: local lighting, as in the paper's figure). Planes
// are shaded as in iso mode, their soft shadows read from their grids or
// marched. Samples are lit one at a time, as CPU packets (two moments; the
// packets read the volume through AnyVoxelSampler, occlusion_map_packets.cpp)
// or on the CUDA device (through AnyVoxelSampler, occlusion_map_device.cu).
template <int K, class Sampler> struct DvrOcclusionLighting {
  const OcclusionShadingSetup<K>* setup;
  Sampler sampler;
  Shading shading;
  const VolumeView* shadow_grids = nullptr;
  VolumeView ambient_grid;
  float ambient_scale = 1.0f;  // AO per grid unit (kUnorm16Step for 16-bit texels)

  // The device copy (backends/device.h): the setup, the grids and the
  // sampler's voxels mirrored (AnyVoxelSampler only).
  template <class Mirror> DvrOcclusionLighting on_device(Mirror& m) const {
    DvrOcclusionLighting d = *this;
    const VolumeView volume = m.volume(setup->lit_view->volume, true, "the volume");
    d.sampler = Sampler(volume.data, volume.dims, volume.type);
    d.setup = setup->on_device(m);
    if (shadow_grids) d.shadow_grids = m.volumes(shadow_grids, m.light_count(), "the DVR shadow grids");
    if (ambient_grid.data) d.ambient_grid = m.volume(ambient_grid, false, "the DVR ambient occlusion grid");
    return d;
  }

  template <class L>
  PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Float ambient_at(const SamplePointL<L>& p,
                                                                 typename L::Mask active) const {
    const OcclusionShadingSetup<K>& s = *setup;
    if (!s.ambient_occlusion) return typename L::Float(1.0f);
    if (ambient_grid.data) return sample_world<L>(ambient_grid, p.world) * ambient_scale;
    return dvr_ambient<L>(s.queries, s.normalise, s.lit_view->volume, sampler, p.index, p.world, p.value, active);
  }

  template <class L>
  PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Vec3 sample(const SamplePointL<L>& p, typename L::Mask active) const {
    const OcclusionShadingSetup<K>& s = *setup;
    const typename L::Float ao = ambient_at<L>(p, active);
    const ScatteringLighting<DvrVisibility> lighting{s.lit_view, DvrVisibility{shadow_grids, s.lit_view->box},
                                                     shading};
    const typename L::Vec3 lit = lighting.template sample<L>(p, active);
    return (s.ao_on_lights ? lit * ao : lit) + s.lit_view->material.albedo * p.color * (s.ambient * ao);
  }
  PENUMBRA_HD vec3 sample(const SamplePoint& p) const { return sample<ScalarLanes>(p, true); }

  PENUMBRA_HD vec3 plane(const PlaneHit& h) const { return IsosurfaceShader<K, Sampler>{setup, sampler}.plane(h); }
};

PENUMBRA_PACKET_LIGHTING(DvrOcclusionLighting<2, AnyVoxelSampler>);
PENUMBRA_DEVICE_LIGHTING(DvrOcclusionLighting<2, AnyVoxelSampler>);
PENUMBRA_DEVICE_LIGHTING(DvrOcclusionLighting<4, AnyVoxelSampler>);

}  // namespace penumbra

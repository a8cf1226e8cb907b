#pragma once
// shadow-rays' light visibility for ScatteringLighting: a shadow ray marched
// from the sample to the light (march_transmittance), or the per-light
// shadow cache inside the volume box. Both are written once over the lane
// type: a packet marches its lanes' shadow rays together. With
// light_samples > 1 a light with an extent is sampled by that many shadow
// rays (area_light_transmittance.h); otherwise one ray toward its centre.
// In a scene with meshes each shadow ray also crosses the meshes' media
// (mesh_transmittance, render/mesh_media.h); the shadow cache holds the
// volume alone, and the meshes' transmittance is marched per lookup.
#include "penumbra/render/lighting.h"
#include "penumbra/render/march.h"
#include "penumbra/render/mesh_media.h"
#include "penumbra/techniques/shadow_rays/area_light_transmittance.h"
#include "penumbra/volume/volume_sampler.h"

namespace penumbra {

struct ShadowRayVisibility {
  const RenderView* view;  // the shadow view (shadow TF, its majorants)
  float density_scale;
  int light_samples = 1;   // shadow rays per light with an extent
  MeshesView meshes{};     // the scene's meshes with their BVHs (count 0: none; never on the device)
  float mesh_step = 1.0f;  // the marching step inside meshes (world units)

  template <class Mirror> ShadowRayVisibility on_device(Mirror& m) const {
    return ShadowRayVisibility{m.view(*view), density_scale, light_samples};
  }

  PENUMBRA_HD bool samples_area(int light) const {
    return light_samples > 1 && light_has_extent(view->lights[light]);
  }

  PENUMBRA_HD vec3 operator()(int light, vec3 p, const LightSample& ls) const {
    if (samples_area(light) || meshes.count > 0) return lanes<ScalarLanes>(light, p, ls, true);
    RayStats unused;
    return vec3(march_transmittance(*view, Ray{p, ls.to_light}, ls.distance, density_scale, unused));
  }

  template <class L>
  PENUMBRA_HD typename L::Vec3 lanes(int light, const typename L::Vec3& p, const LightSampleL<L>& ls,
                                     typename L::Mask active) const {
    return transmittance<L>(light, p, ls, active, true);
  }

  // The meshes' part of the visibility alone (1 without meshes).
  template <class L>
  PENUMBRA_HD typename L::Vec3 mesh_visibility(int light, const typename L::Vec3& p, const LightSampleL<L>& ls,
                                               typename L::Mask active) const {
    if (meshes.count == 0) return typename L::Vec3(1.0f);
    return transmittance<L>(light, p, ls, active, false);
  }

  // Through the volume (when `volume`) and the meshes (per channel: their
  // transport colours), toward the light's centre or, for an area light,
  // the mean over its samples of each shadow ray's product.
  template <class L>
  PENUMBRA_HD typename L::Vec3 transmittance(int light, const typename L::Vec3& p, const LightSampleL<L>& ls,
                                             typename L::Mask active, bool volume) const {
    using F = typename L::Float;
    using V = typename L::Vec3;
    constexpr int W = L::kWidth;
    vec3 origins[W];
    unpack_lanes<L>(p, origins);
    const AnyVoxelSampler sampler(view->volume.data, view->volume.dims, view->volume.type);
    RayStats unused;
    const auto along = [&](const Ray* rays, const float* distances) {
      V t(volume ? march_transmittance<L>(*view, sampler, rays, distances, density_scale, active, unused) : F(1.0f));
      if (meshes.count > 0) {
        t = t * mesh_transmittance<L>(meshes, rays, distances, mesh_step, density_scale, active, unused.samples);
      }
      return t;
    };
    if (samples_area(light)) return area_light_mean<L>(view->lights[light], light, origins, light_samples, along);
    vec3 directions[W];
    unpack_lanes<L>(ls.to_light, directions);
    Ray rays[W];
    float distances[W];
    L::store(ls.distance, distances);
    for (int i = 0; i < W; ++i) rays[i] = Ray{origins[i], directions[i]};
    return along(rays, distances);
  }
};

// Cache lookups inside the volume box; outside it (plane hits) the cache where
// the shadow ray enters the box, or with light_samples > 1 a shadow ray.
// With meshes, times their transmittance (the cache holds the volume's).
struct CachedShadowRayVisibility {
  ShadowRayVisibility rays;
  const VolumeView* caches;  // per light

  template <class Mirror> CachedShadowRayVisibility on_device(Mirror& m) const {
    return CachedShadowRayVisibility{rays.on_device(m), m.volumes(caches, m.light_count(), "the shadow caches")};
  }

  PENUMBRA_HD vec3 operator()(int light, vec3 p, const LightSample& ls) const {
    return lanes<ScalarLanes>(light, p, ls, true);
  }
  template <class L>
  PENUMBRA_HD typename L::Vec3 lanes(int light, const typename L::Vec3& p, const LightSampleL<L>& ls,
                                     typename L::Mask active) const {
    using V = typename L::Vec3;
    // An area light's cached mean over its extent depends on the distance to
    // it, so plane hits march their rays; one ray per light looks up the
    // cache where its ray enters the box.
    V cached;
    if (rays.samples_area(light)) {
      cached = cached_visibility<L>(caches[light], rays.view->box, volume_rays(), light, p, ls, active);
    } else {
      cached = entry_cached_visibility<L>(caches[light], rays.view->box, volume_rays(), light, p, ls, active);
    }
    if (rays.meshes.count == 0) return cached;
    return cached * rays.mesh_visibility<L>(light, p, ls, active);
  }

 private:
  PENUMBRA_HD ShadowRayVisibility volume_rays() const {
    return ShadowRayVisibility{rays.view, rays.density_scale, rays.light_samples};
  }
};

PENUMBRA_PACKET_LIGHTING(ScatteringLighting<ShadowRayVisibility>);
PENUMBRA_PACKET_LIGHTING(ScatteringLighting<CachedShadowRayVisibility>);
PENUMBRA_DEVICE_LIGHTING(ScatteringLighting<ShadowRayVisibility>);
PENUMBRA_DEVICE_LIGHTING(ScatteringLighting<CachedShadowRayVisibility>);

}  // namespace penumbra

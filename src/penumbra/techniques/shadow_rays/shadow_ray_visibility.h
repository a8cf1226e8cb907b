#pragma once
// shadow-rays' light visibility for ScatteringLighting: a shadow ray marched
// from the sample to the light (march_transmittance), or the per-light
// shadow cache inside the volume box. Both are written once over the lane
// type: a packet marches its lanes' shadow rays together. With
// light_samples > 1 a light with an extent is sampled by that many shadow
// rays (area_light_transmittance.h); otherwise one ray toward its centre.
#include "penumbra/render/lighting.h"
#include "penumbra/render/march.h"
#include "penumbra/techniques/shadow_rays/area_light_transmittance.h"
#include "penumbra/volume/volume_sampler.h"

namespace penumbra {

struct ShadowRayVisibility {
  const RenderView* view;  // the shadow view (shadow TF, its majorants)
  float density_scale;
  int light_samples = 1;  // shadow rays per light with an extent

  template <class Mirror> ShadowRayVisibility on_device(Mirror& m) const {
    return ShadowRayVisibility{m.view(*view), density_scale, light_samples};
  }

  PENUMBRA_HD bool samples_area(int light) const {
    return light_samples > 1 && light_has_extent(view->lights[light]);
  }

  PENUMBRA_HD vec3 operator()(int light, vec3 p, const LightSample& ls) const {
    if (samples_area(light)) return lanes<ScalarLanes>(light, p, ls, true);
    RayStats unused;
    return vec3(march_transmittance(*view, Ray{p, ls.to_light}, ls.distance, density_scale, unused));
  }

  template <class L>
  PENUMBRA_HD typename L::Vec3 lanes(int light, const typename L::Vec3& p, const LightSampleL<L>& ls,
                                     typename L::Mask active) const {
    constexpr int W = L::kWidth;
    vec3 origins[W], directions[W];
    unpack_lanes<L>(p, origins);
    const AnyVoxelSampler sampler(view->volume.data, view->volume.dims, view->volume.type);
    RayStats unused;
    if (samples_area(light)) {
      return typename L::Vec3(area_light_transmittance<L>(*view, sampler, view->lights[light], light, origins,
                                                          light_samples, density_scale, active, unused));
    }
    unpack_lanes<L>(ls.to_light, directions);
    Ray rays[W];
    float distances[W];
    L::store(ls.distance, distances);
    for (int i = 0; i < W; ++i) rays[i] = Ray{origins[i], directions[i]};
    return typename L::Vec3(
        march_transmittance<L>(*view, sampler, rays, distances, density_scale, active, unused));
  }
};

// Cache lookups inside the volume box; outside it (plane hits) the cache where
// the shadow ray enters the box, or with light_samples > 1 a shadow ray.
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
    // An area light's cached mean over its extent depends on the distance to
    // it, so plane hits march their rays; one ray per light looks up the
    // cache where its ray enters the box.
    if (rays.samples_area(light)) return cached_visibility<L>(caches[light], rays.view->box, rays, light, p, ls, active);
    return entry_cached_visibility<L>(caches[light], rays.view->box, rays, light, p, ls, active);
  }
};

PENUMBRA_PACKET_LIGHTING(ScatteringLighting<ShadowRayVisibility>);
PENUMBRA_PACKET_LIGHTING(ScatteringLighting<CachedShadowRayVisibility>);
PENUMBRA_DEVICE_LIGHTING(ScatteringLighting<ShadowRayVisibility>);
PENUMBRA_DEVICE_LIGHTING(ScatteringLighting<CachedShadowRayVisibility>);

}  // namespace penumbra

#pragma once
// filtered-sat's light visibility for ScatteringLighting: the transmittance
// exp(-density_scale * filtered optical depth), from the tables per sample
// or from the per-light shadow cache inside the volume box (Algorithm 1).
#include "penumbra/render/lighting.h"
#include "penumbra/scene/light.h"
#include "penumbra/techniques/filtered_sat/light_tables.h"
#include "penumbra/volume/volume_view.h"

namespace penumbra {

struct FilteredVisibility {
  const LightTableLookup* lights = nullptr;
  ShadowFilter filter;

  PENUMBRA_HD float transmittance(int light, vec3 p) const {
    return exp_nonpositive(-filter.density_scale * filtered_optical_depth(lights[light], filter, p));
  }
  PENUMBRA_HD vec3 operator()(int light, vec3 p, const LightSample&) const { return vec3(transmittance(light, p)); }
};

// Cache lookups inside the volume box; the tables elsewhere (plane hits).
struct CachedFilteredVisibility {
  FilteredVisibility direct;
  const VolumeView* caches = nullptr;  // per light; data == nullptr for lights without a cache
  Box3 box;

  PENUMBRA_HD vec3 operator()(int light, vec3 p, const LightSample& ls) const {
    return lanes<ScalarLanes>(light, p, ls, true);
  }
  template <class L>
  PENUMBRA_HD typename L::Vec3 lanes(int light, const typename L::Vec3& p, const LightSampleL<L>& ls,
                                     typename L::Mask active) const {
    return cached_visibility<L>(caches[light], box, direct, light, p, ls, active);
  }
};

PENUMBRA_PACKET_LIGHTING(ScatteringLighting<FilteredVisibility>);
PENUMBRA_PACKET_LIGHTING(ScatteringLighting<CachedFilteredVisibility>);

}  // namespace penumbra

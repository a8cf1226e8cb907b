#pragma once
// The sat-ao kernel: occlusion from the mean extinction around a point.
#include "penumbra/render/lighting.h"
#include "penumbra/scene/light.h"
#include "penumbra/techniques/sat_common/cartesian_table_grid.h"
#include "penumbra/techniques/sat_common/summed_area_table.h"
#include "penumbra/volume/volume_view.h"

namespace penumbra {

struct AmbientOcclusion {
  SummedAreaTableView table;
  CartesianTableGrid grid;  // volume-aligned
  float radius = 1.0f;      // world units
  float density_scale = 1.0f;

  template <class Mirror> AmbientOcclusion on_device(Mirror& m) const {
    AmbientOcclusion d = *this;
    d.table = table.on_device(m);
    return d;
  }

  // exp(-sigma_mean R) with sigma_mean the mean extinction of the cube
  // [p - R, p + R]^3 (outside the volume counts as empty).
  PENUMBRA_HD float occlusion(vec3 p) const {
    const vec3 q = grid.grid_from_world(p);
    const float r = radius / grid.cell;
    const double sum = table.box_sum(q - r, q + r);
    const double cube = 8.0 * double(radius) * radius * radius;
    return exp_nonpositive(-density_scale * float(glm::max(sum / cube, 0.0)) * radius);
  }
  PENUMBRA_HD vec3 operator()(int, vec3 p, const LightSample&) const { return vec3(occlusion(p)); }
};

// The occlusion from a cache inside the volume box, from the table elsewhere.
struct CachedAmbientOcclusion {
  AmbientOcclusion direct;
  VolumeView cache;
  Box3 box;

  template <class Mirror> CachedAmbientOcclusion on_device(Mirror& m) const {
    return CachedAmbientOcclusion{direct.on_device(m), m.volume(cache, false, "the occlusion cache"), box};
  }
  PENUMBRA_HD vec3 operator()(int light, vec3 p, const LightSample& ls) const {
    return lanes<ScalarLanes>(light, p, ls, true);
  }
  template <class L>
  PENUMBRA_HD typename L::Vec3 lanes(int light, const typename L::Vec3& p, const LightSampleL<L>& ls,
                                     typename L::Mask active) const {
    return cached_visibility<L>(cache, box, direct, light, p, ls, active);
  }
};

PENUMBRA_PACKET_LIGHTING(ScatteringLighting<AmbientOcclusion>);
PENUMBRA_PACKET_LIGHTING(ScatteringLighting<CachedAmbientOcclusion>);
PENUMBRA_DEVICE_LIGHTING(ScatteringLighting<AmbientOcclusion>);
PENUMBRA_DEVICE_LIGHTING(ScatteringLighting<CachedAmbientOcclusion>);

}  // namespace penumbra

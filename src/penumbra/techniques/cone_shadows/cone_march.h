#pragma once
// The cone-shadows kernel: optical depth along a cone of growing cubes.
#include "penumbra/base/ray.h"
#include "penumbra/render/lighting.h"
#include "penumbra/scene/light.h"
#include "penumbra/techniques/sat_common/cartesian_table_grid.h"
#include "penumbra/techniques/sat_common/plane_caches.h"
#include "penumbra/techniques/sat_common/summed_area_table.h"
#include "penumbra/volume/volume_view.h"

namespace penumbra {

struct ConeMarch {
  SummedAreaTableView table;
  CartesianTableGrid grid;  // volume-aligned
  Box3 box;                 // the volume box: the cone ends where its axis leaves it
  float tan_half_angle = 0.0f;  // the cone of lights without a derived one
  float step = 1.0f;        // world units
  float density_scale = 1.0f;
  // The cone derived from each light's size (cone_shadows.h), for the first
  // kDerivedLights lights: light_tan >= 0 a fixed tan(half-angle) (distant
  // lights), light_radius > 0 a sphere or disk whose cone follows the
  // distance (r / sqrt(d^2 - r^2)); neither: tan_half_angle.
  static constexpr int kDerivedLights = 8;
  float light_tan[kDerivedLights] = {-1.0f, -1.0f, -1.0f, -1.0f, -1.0f, -1.0f, -1.0f, -1.0f};
  float light_radius[kDerivedLights] = {};

  // tan(half-angle) of the cone toward light `light` at `distance`.
  PENUMBRA_HD float cone_tan(int light, float distance) const {
    if (light < 0 || light >= kDerivedLights) return tan_half_angle;
    if (light_tan[light] >= 0.0f) return light_tan[light];
    const float r = light_radius[light];
    if (r > 0.0f) return distance > 1.001f * r ? r / glm::sqrt(distance * distance - r * r) : 22.4f;  // 87 degrees
    return tan_half_angle;
  }

  template <class Mirror> ConeMarch on_device(Mirror& m) const {
    ConeMarch d = *this;
    d.table = table.on_device(m);
    return d;
  }

  // Optical depth from p toward a light `distance` away along unit
  // `to_light`, through the cone of tan(half-angle) `tan_half`.
  PENUMBRA_HD float optical_depth(vec3 p, vec3 to_light, float distance) const {
    return optical_depth(p, to_light, distance, tan_half_angle);
  }
  PENUMBRA_HD float optical_depth(vec3 p, vec3 to_light, float distance, float tan_half) const {
    const Interval chord = intersect_box(Ray{p, to_light}, box, 0.0f, distance);
    if (chord.empty()) return 0.0f;
    double depth = 0.0;
    for (float t = 0.0f; t < chord.t1; t += step) {
      const float length = glm::min(step, chord.t1 - t);
      const float middle = t + 0.5f * length;
      const float half = glm::max(middle * tan_half, 0.5f * length);
      const vec3 q = grid.grid_from_world(p + middle * to_light);
      const float h = half / grid.cell;
      const double cube = 8.0 * double(half) * half * half;
      depth += table.box_sum(q - h, q + h) / cube * double(length);
    }
    return float(glm::max(depth, 0.0));
  }
  PENUMBRA_HD float transmittance(int light, vec3 p, const LightSample& ls) const {
    // A light that sends nothing here (an environment light) needs no cone.
    if (ls.radiance == vec3(0.0f)) return 1.0f;
    return exp_nonpositive(-density_scale * optical_depth(p, ls.to_light, ls.distance, cone_tan(light, ls.distance)));
  }
  PENUMBRA_HD vec3 operator()(int light, vec3 p, const LightSample& ls) const {
    return vec3(transmittance(light, p, ls));
  }
};

// Per-light caches inside the volume box and on the opaque planes, the cone
// march elsewhere.
struct CachedConeMarch {
  ConeMarch direct;
  const VolumeView* caches = nullptr;  // per light; data == nullptr: no cache
  PlaneCachesView planes;              // per light and plane (cone_shadows.cpp)

  template <class Mirror> CachedConeMarch on_device(Mirror& m) const {
    return CachedConeMarch{direct.on_device(m), m.volumes(caches, m.light_count(), "the shadow caches"),
                           planes.on_device(m)};
  }
  PENUMBRA_HD vec3 operator()(int light, vec3 p, const LightSample& ls) const {
    return lanes<ScalarLanes>(light, p, ls, true);
  }
  // A point on opaque plane `plane`: its cache, or the cone march without one.
  PENUMBRA_HD vec3 plane(int light, int plane, vec3 p, const LightSample& ls) const {
    if (planes.has(light, plane)) return vec3(planes.sample(light, plane, p));
    return direct(light, p, ls);
  }
  template <class L>
  PENUMBRA_HD typename L::Vec3 lanes(int light, const typename L::Vec3& p, const LightSampleL<L>& ls,
                                     typename L::Mask active) const {
    return cached_visibility<L>(caches[light], direct.box, direct, light, p, ls, active);
  }
};

PENUMBRA_PACKET_LIGHTING(ScatteringLighting<ConeMarch>);
PENUMBRA_PACKET_LIGHTING(ScatteringLighting<CachedConeMarch>);
PENUMBRA_DEVICE_LIGHTING(ScatteringLighting<ConeMarch>);
PENUMBRA_DEVICE_LIGHTING(ScatteringLighting<CachedConeMarch>);

}  // namespace penumbra

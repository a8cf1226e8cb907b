#pragma once
// The ambient-scattering kernels: a tube of spheres toward each light, each
// sphere's mean extinction from the volume-aligned SAT, and the
// preintegrated scattering table (scattering_table.h) for what each sphere
// passes on and what the sample's own sphere scatters toward the viewer.
#include "penumbra/base/ray.h"
#include "penumbra/render/lighting.h"
#include "penumbra/scene/camera.h"
#include "penumbra/scene/light.h"
#include "penumbra/techniques/ambient_scattering/scattering_table.h"
#include "penumbra/techniques/sat_common/cartesian_table_grid.h"
#include "penumbra/techniques/sat_common/plane_caches.h"
#include "penumbra/techniques/sat_common/summed_area_table.h"
#include "penumbra/volume/volume_view.h"

namespace penumbra {

// A volume-aligned SAT sums boxes: a sphere's mean extinction is read over
// its bounding cube [c - R, c + R]^3 (sat-ao's cube), so the cubes of
// consecutive tube spheres, 2R apart, abut along the axis and a thin
// occluder cannot fall between them (the cube of the sphere's volume,
// half-width 0.81 R, left gaps of 0.39 R that a 2-voxel layer fell into at
// R = 8, ambient_scattering_test.cpp).
struct AmbientTube {
  SummedAreaTableView table;
  CartesianTableGrid grid;  // volume-aligned
  Box3 box;                 // the volume box
  float radius = 1.0f;      // R, world units; tube steps are 2 R
  float density_scale = 1.0f;
  ScatteringTableView scattering;
  // Where the viewing rays come from: a sample's view direction is the
  // direction from the eye (or the orthographic forward axis), as its ray's.
  CameraView camera;

  template <class Mirror> AmbientTube on_device(Mirror& m) const {
    AmbientTube d = *this;
    d.table = table.on_device(m);
    d.scattering = scattering.on_device(m);
    return d;
  }

  // tau = sigma_mean R of the sphere of radius R around p (outside the
  // volume counts as empty).
  PENUMBRA_HD float optical_radius(vec3 p) const {
    const vec3 q = grid.grid_from_world(p);
    const float h = radius / grid.cell;
    const double mass = table.box_sum(q - h, q + h);
    const double volume = 8.0 * double(radius) * radius * radius;
    return density_scale * float(glm::max(mass / volume, 0.0)) * radius;
  }

  // The light the tube passes on to the surface of p's sphere: spheres of
  // radius R centred 2R, 4R, ... from p toward the light, each passing on
  // F(its tau) of what enters it, up to where the axis leaves the volume
  // box grown by R (or reaches the light).
  PENUMBRA_HD float tube_transfer(vec3 p, vec3 to_light, float distance) const {
    const Box3 reach{box.lower - vec3(radius), box.upper + vec3(radius)};
    const Interval chord = intersect_box(Ray{p, to_light}, reach, 0.0f, distance);
    if (chord.empty()) return 1.0f;
    const float step = 2.0f * radius;
    // The first sphere whose far side passes the chord's start.
    int k = glm::max(1, int(glm::ceil((chord.t0 - radius) / step)));
    float transfer = 1.0f;
    for (; float(k) * step - radius < chord.t1; ++k) {
      transfer *= scattering.tube_transfer(optical_radius(p + (float(k) * step) * to_light));
      if (transfer < 1e-8f) return 0.0f;
    }
    return transfer;
  }

  PENUMBRA_HD vec3 view_direction(vec3 p) const {
    return camera.orthographic ? camera.forward : glm::normalize(p - camera.eye);
  }

  // A volume sample: the tube times the own sphere's in-scattering toward
  // the viewer over the phase function the shared lighting applies.
  PENUMBRA_HD float sample_visibility(vec3 p, const LightSample& ls) const {
    const float mu = glm::dot(ls.to_light, view_direction(p));
    return tube_transfer(p, ls.to_light, ls.distance) *
           scattering.in_scattering<ScalarLanes>(optical_radius(p), mu);
  }
  // A surface point (an opaque plane): the tube times the forward
  // irradiance at its own sphere's centre.
  PENUMBRA_HD float surface_visibility(vec3 p, const LightSample& ls) const {
    return tube_transfer(p, ls.to_light, ls.distance) * scattering.surface_transfer(optical_radius(p));
  }

  PENUMBRA_HD vec3 operator()(int, vec3 p, const LightSample& ls) const {
    // A light that sends nothing here (an environment light) needs no tube.
    if (ls.radiance == vec3(0.0f)) return vec3(1.0f);
    return vec3(sample_visibility(p, ls));
  }
  PENUMBRA_HD vec3 plane(int, int, vec3 p, const LightSample& ls) const {
    if (ls.radiance == vec3(0.0f)) return vec3(1.0f);
    return vec3(surface_visibility(p, ls));
  }
};

// The shadow cache: per light the tube transfer at each texel, one grid of
// the own spheres' optical radii for all lights, and per light and plane the
// surface visibility (sat_common/plane_caches.h). The in-scattering lookup
// depends on the view, so it stays per sample: one table read after the two
// grid reads (the paper's "additional view-dependent lookup").
struct CachedAmbientTube {
  AmbientTube direct;
  const VolumeView* tubes = nullptr;  // per light; data == nullptr: no cache (environment lights)
  VolumeView optical_radii;
  PlaneCachesView planes;

  template <class Mirror> CachedAmbientTube on_device(Mirror& m) const {
    return CachedAmbientTube{direct.on_device(m), m.volumes(tubes, m.light_count(), "the tube caches"),
                             m.volume(optical_radii, false, "the optical radius cache"), planes.on_device(m)};
  }
  PENUMBRA_HD vec3 operator()(int light, vec3 p, const LightSample& ls) const {
    return lanes<ScalarLanes>(light, p, ls, true);
  }
  PENUMBRA_HD vec3 plane(int light, int plane, vec3 p, const LightSample& ls) const {
    if (planes.has(light, plane)) return vec3(planes.sample(light, plane, p));
    return direct.plane(light, plane, p, ls);
  }
  template <class L>
  PENUMBRA_HD typename L::Vec3 lanes(int light, const typename L::Vec3& p, const LightSampleL<L>& ls,
                                     typename L::Mask active) const {
    using F = typename L::Float;
    using V = typename L::Vec3;
    const VolumeView& tube = tubes[light];
    if (!tube.data) return light_visibility<L>(direct, light, p, ls, active);
    const auto inside = box_contains<L>(direct.box, p);
    if constexpr (L::kWidth == 1) {
      if (!inside) return direct(light, p, ls);
    }
    const V view = direct.camera.orthographic ? V(direct.camera.forward) : normalize(p - V(direct.camera.eye));
    const F m = direct.scattering.in_scattering<L>(sample_world<L>(optical_radii, p), dot(ls.to_light, view));
    V result(sample_world<L>(tube, p) * m);
    if constexpr (L::kWidth > 1) {
      const auto outside = active & !inside;
      if (any(outside)) result = select(outside, light_visibility<L>(direct, light, p, ls, outside), result);
    }
    return result;
  }
};

PENUMBRA_PACKET_LIGHTING(ScatteringLighting<AmbientTube>);
PENUMBRA_PACKET_LIGHTING(ScatteringLighting<CachedAmbientTube>);
PENUMBRA_DEVICE_LIGHTING(ScatteringLighting<AmbientTube>);
PENUMBRA_DEVICE_LIGHTING(ScatteringLighting<CachedAmbientTube>);

}  // namespace penumbra

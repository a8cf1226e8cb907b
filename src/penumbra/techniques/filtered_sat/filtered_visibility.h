#pragma once
// filtered-sat's light visibility for ScatteringLighting: the transmittance
// exp(-density_scale * filtered optical depth), from the tables per sample
// or from the per-light shadow cache inside the volume box (Algorithm 1).
#include "penumbra/render/lighting.h"
#include "penumbra/scene/light.h"
#include "penumbra/techniques/filtered_sat/light_tables.h"
#include "penumbra/techniques/sat_common/plane_caches.h"
#include "penumbra/techniques/sat_common/refined_cells.h"
#include "penumbra/techniques/sat_common/visibility_cache.h"
#include "penumbra/volume/volume_sampler.h"
#include "penumbra/volume/volume_view.h"

#include <vector>

namespace penumbra {

struct FilteredVisibility {
  // Lights 0 .. kLightFilters - 1 have a filter each (from their sizes,
  // filtered_sat.h); the others share filters[kLightFilters].
  static constexpr int kLightFilters = 8;
  const LightTableLookup* lights = nullptr;
  ShadowFilter filters[kLightFilters + 1];

  // `per_light[i]` for light i, `shared` for the lights beyond them.
  static FilteredVisibility with(const LightTableLookup* lights, const std::vector<ShadowFilter>& per_light,
                                 const ShadowFilter& shared) {
    FilteredVisibility v;
    v.lights = lights;
    for (int i = 0; i < kLightFilters; ++i) v.filters[i] = std::size_t(i) < per_light.size() ? per_light[i] : shared;
    v.filters[kLightFilters] = shared;
    return v;
  }

  // The device copy (backends/device.h): each light's table mirrored.
  template <class Mirror> FilteredVisibility on_device(Mirror& m) const {
    std::vector<LightTableLookup> copy(lights, lights + m.light_count());
    for (LightTableLookup& light : copy) light.table = light.table.on_device(m);
    FilteredVisibility v = *this;
    v.lights = m.frame(copy, "the light tables");
    return v;
  }

  PENUMBRA_HD const ShadowFilter& filter(int light) const {
    return filters[light < kLightFilters ? light : kLightFilters];
  }
  // The filtered optical depth times the density scale.
  PENUMBRA_HD float optical_depth(int light, vec3 p) const {
    const ShadowFilter& f = filter(light);
    return f.density_scale * filtered_optical_depth(lights[light], f, p);
  }
  PENUMBRA_HD float transmittance(int light, vec3 p) const { return exp_nonpositive(-optical_depth(light, p)); }
  PENUMBRA_HD vec3 operator()(int light, vec3 p, const LightSample&) const { return vec3(transmittance(light, p)); }
};

// The volume box grown so that beyond its projection along a light the
// filtered visibility is 1 (the plane grids' region): a sample's patch
// reaches sqrt(2) half-widths sideways (its corners), and a table lookup's
// interpolation two table cells more. Unlike a cone ending where its axis
// leaves the box, a patch beside the box's shadow still sees it.
inline Box3 filtered_shadow_box(const Box3& box, const ShadowFilter& filter, float table_cell) {
  const float reach = 1.41421356f * filter.half_width + 2.0f * table_cell;
  return Box3{box.lower - vec3(reach), box.upper + vec3(reach)};
}

// A trilinear read of a 16-bit visibility cache (unorm16_visibility) at
// world positions, and the spread (largest minus smallest) of the 8 texels
// it interpolates: a bound on how far the interpolation can be from the
// visibility anywhere in the cell.
template <class L>
PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Float cache_read_with_spread(const VolumeView& cache,
                                                                           const typename L::Vec3& world,
                                                                           typename L::Float& spread) {
  using F = typename L::Float;
  using V = typename L::Vec3;
  using X = typename L::Index;
  const VoxelGrid g(cache.dims);
  const GridCell<L> cell(g, (world - V(cache.origin)) / V(cache.spacing));
  const std::uint16_t* data = static_cast<const std::uint16_t*>(cache.data);
  F c000, c100, c010, c110, c001, c101, c011, c111;
  load_voxel_pair(data, cell.base, g.stride_x, g.count, c000, c100);
  load_voxel_pair(data, cell.base + X(g.stride_y), g.stride_x, g.count, c010, c110);
  load_voxel_pair(data, cell.base + X(g.stride_z), g.stride_x, g.count, c001, c101);
  load_voxel_pair(data, cell.base + X(g.stride_y + g.stride_z), g.stride_x, g.count, c011, c111);
  const F hi = max(max(max(c000, c100), max(c010, c110)), max(max(c001, c101), max(c011, c111)));
  const F lo = min(min(min(c000, c100), min(c010, c110)), min(min(c001, c101), min(c011, c111)));
  spread = (hi - lo) * kUnorm16Step;
  const F x00 = c000 + cell.fx * (c100 - c000);
  const F x10 = c010 + cell.fx * (c110 - c010);
  const F x01 = c001 + cell.fx * (c101 - c001);
  const F x11 = c011 + cell.fx * (c111 - c011);
  const F y0 = x00 + cell.fy * (x10 - x00);
  const F y1 = x01 + cell.fy * (x11 - x01);
  return (y0 + cell.fz * (y1 - y0)) * kUnorm16Step;
}

// A rough cache cell's refined brick (refined_cells.h), or the cache's own
// trilinear read in a cell without one; the lane-by-lane form of the rough
// lanes of CachedFilteredVisibility.
struct RefinedCacheRead {
  const VolumeView* caches = nullptr;
  const RefinedCellsView* refined = nullptr;
  PENUMBRA_HD vec3 operator()(int light, vec3 p, const LightSample&) const {
    float value;
    if (!refined[light].sample(caches[light], p, value)) {
      float spread;
      value = cache_read_with_spread<ScalarLanes>(caches[light], p, spread);
    }
    return vec3(value);
  }
};

// Cache lookups inside the volume box where the cache is smooth, the tables
// outside it. In cache cells whose texels differ by more than `tolerance`
// (where the transmittance jumps, at lit surfaces, interpolating it would
// smear the shadow of the material behind the surface onto the surface;
// issue 22): the cell's refined brick, or the tables without bricks
// (`refined` null). A tolerance of 1 or more reads the cache everywhere
// inside the box. Plane hits read the light's grid on that plane
// (`planes`), or the tables where it has none.
struct CachedFilteredVisibility {
  FilteredVisibility direct;
  const VolumeView* caches = nullptr;  // per light; data == nullptr for lights without a cache
  Box3 box;
  float tolerance = 1.0f;
  const RefinedCellsView* refined = nullptr;  // per light, or null: the tables in rough cells
  const PlaneCachesView* planes = nullptr;    // per light (its light 0), or null: the tables on planes

  template <class Mirror> CachedFilteredVisibility on_device(Mirror& m) const {
    const RefinedCellsView* device_refined = nullptr;
    if (refined) {
      std::vector<RefinedCellsView> copy(refined, refined + m.light_count());
      for (RefinedCellsView& r : copy) {
        const std::size_t blocks = std::size_t(r.blocks.x) * r.blocks.y * r.blocks.z;
        if (r.depth_of_code) r.depth_of_code = m.structure(r.depth_of_code, 256, "the bricks' depth table");
        for (int l = 0; l < r.levels; ++l) {
          BrickLevelView& v = r.level[l];
          if (v.bricks == 0) continue;
          const std::size_t n = std::size_t(v.refine);
          v.block_first = m.structure(v.block_first, blocks, "the shadow caches' refined cells");
          v.block_mask = m.structure(v.block_mask, blocks, "the shadow caches' refined cells");
          v.texels = m.structure(v.texels, std::size_t(v.bricks) * n * n * n, "the shadow caches' refined cells");
        }
      }
      device_refined = m.frame(copy, "the shadow caches' refined cells");
    }
    const PlaneCachesView* device_planes = nullptr;
    if (planes) {
      std::vector<PlaneCachesView> copy(planes, planes + m.light_count());
      for (PlaneCachesView& p : copy) p = p.on_device(m);
      device_planes = m.frame(copy, "the plane shadow caches");
    }
    return CachedFilteredVisibility{direct.on_device(m), m.volumes(caches, m.light_count(), "the shadow caches"), box,
                                    tolerance, device_refined, device_planes};
  }

  // A point on opaque plane `plane`: the light's grid there, or the tables.
  PENUMBRA_HD vec3 plane(int light, int plane, vec3 p, const LightSample& ls) const {
    if (planes && planes[light].has(0, plane)) return vec3(planes[light].sample(0, plane, p));
    return direct(light, p, ls);
  }
  PENUMBRA_HD vec3 operator()(int light, vec3 p, const LightSample& ls) const {
    return lanes<ScalarLanes>(light, p, ls, true);
  }
  template <class L>
  PENUMBRA_HD typename L::Vec3 lanes(int light, const typename L::Vec3& p, const LightSampleL<L>& ls,
                                     typename L::Mask active) const {
    using F = typename L::Float;
    using V = typename L::Vec3;
    const VolumeView& cache = caches[light];
    if (!cache.data) return light_visibility<L>(direct, light, p, ls, active);
    F spread;
    const F cached = cache_read_with_spread<L>(cache, p, spread);
    using M = typename L::Mask;
    const M outside = active & !box_contains<L>(box, p);
    const M rough = active & !outside & (spread > tolerance);
    const M tables = refined ? outside : M(outside | rough);
    const M bricks = refined ? rough : M(false);
    if constexpr (L::kWidth == 1) {
      if (tables) return direct(light, p, ls);
      if (bricks) return RefinedCacheRead{caches, refined}(light, p, ls);
      return V(cached);
    } else {
      V result(cached);
      if (any(tables)) result = select(tables, light_visibility<L>(direct, light, p, ls, tables), result);
      if (any(bricks)) {
        result = select(bricks, light_visibility<L>(RefinedCacheRead{caches, refined}, light, p, ls, bricks), result);
      }
      return result;
    }
  }
};

PENUMBRA_PACKET_LIGHTING(ScatteringLighting<FilteredVisibility>);
PENUMBRA_PACKET_LIGHTING(ScatteringLighting<CachedFilteredVisibility>);
PENUMBRA_DEVICE_LIGHTING(ScatteringLighting<FilteredVisibility>);
PENUMBRA_DEVICE_LIGHTING(ScatteringLighting<CachedFilteredVisibility>);

}  // namespace penumbra

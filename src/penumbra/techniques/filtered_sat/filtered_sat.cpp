#include "penumbra/techniques/filtered_sat/filtered_sat.h"

#include "penumbra/base/error.h"
#include "penumbra/render/render_lit.h"
#include "penumbra/render/scene_resources.h"
#include "penumbra/techniques/filtered_sat/filtered_visibility.h"
#include "penumbra/techniques/filtered_sat/streamed_table.h"
#include "penumbra/techniques/sat_common/extinction_table.h"
#include "penumbra/techniques/sat_common/plane_caches.h"
#include "penumbra/techniques/sat_common/refined_cells.h"
#include "penumbra/techniques/sat_common/table_dependencies.h"
#include "penumbra/techniques/sat_common/visibility_cache.h"

#include <cassert>
#include <limits>
#include <optional>
#include <vector>

namespace penumbra {
namespace {

// The filter width of lights without a size, and of every light with
// filter_voxels unset before issue 18.
constexpr double kDefaultFilterVoxels = 5.0;
constexpr double kMinFilterVoxels = 0.25, kMaxFilterVoxels = 256.0;  // filter_voxels' range
// Refined cells: a rough cache cell gets a brick where its trilinear read
// misses the cube root of the visibility by more than this at a probe, and
// the coarsest brick whose read misses it by no more halfway between its
// texels (a lightness step of about 116 x 0.007 cbrt(Y) = 0.8 cbrt(Y) L*,
// Y the lit luminance: under 1 L* wherever a cache cell covers many pixels,
// zoomed in). Plane grids: nodes a fifth of the light's filter width apart,
// between a quarter of a voxel and a voxel (a penumbra on the floor is at
// most the filter wide). Chosen by measurement (docs/filtered-sat.md,
// "Memory", "Adaptive bricks" and "Zoomed in").
constexpr float kProbeTolerance = 0.007f;
// table_streaming=auto streams a light's table when it would take more than
// this (docs/filtered-sat.md, "Streamed tables").
constexpr std::uint64_t kStreamTablesAbove = std::uint64_t(512) << 20;
constexpr float kPlaneNodesPerFilter = 5.0f, kMinPlaneNodeVoxels = 0.25f, kMaxPlaneNodeVoxels = 1.0f;

FilterKernel kernel_named(const std::string& name, bool gaussian_light) {
  if (name == "auto") return gaussian_light ? FilterKernel::Gaussian : FilterKernel::Box;
  return name == "gaussian" ? FilterKernel::Gaussian : FilterKernel::Box;
}

class FilteredSat final : public Technique {
 public:
  void prepare(const Scene& scene, const ParameterValues& params) override {
    resources_.update(scene);
    const float voxel = scene.volume().view().min_spacing();
    const std::vector<vec2> previous_shapes = std::move(light_shapes_);
    derive_filters(scene, params, voxel);
    // The tables depend on the extinction (data, shadow TF, clip planes), the
    // resolution and each light's direction or position; a light's colour
    // or intensity, a floor plane or a render-only TF edit change none.
    const RenderView shadows = resources_.shadow_view(scene);
    ExtinctionInputs inputs = extinction_inputs(scene, shadows);
    const double resolution = params.number("sat_resolution");
    const float cell = voxel / float(resolution);
    std::vector<LightTables::Placement> placements = LightTables::plan(scene.lights(), cell);
    const bool same_extinction = built_ && inputs == inputs_ && resolution == table_resolution_;
    if (!same_extinction) caches_.clear();
    std::vector<LightTables::Placement> previous = std::move(placements_);
    placements_ = placements;
    built_ = false;
    const bool cache = params.flag("shadow_cache");
    cache_tolerance_ = float(params.number("cache_tolerance"));
    const int refine = params.integer("cache_refinement");
    if (refine == 1) {
      throw InvalidArgument("cache_refinement", "must be 0 (the tables in rough cells) or at least 2; got 1");
    }
    // Cache cells whose texels differ by more than the tolerance read their
    // refined bricks, built with the cache (or, without refinement or at a
    // tolerance of 0, the tables).
    const bool bricks = cache && refine > 0 && cache_tolerance_ > 0.0f && cache_tolerance_ < 1.0f;
    // Plane hits read a grid per light and plane, filled with the light's
    // cache, where every light with a table gets one on every plane.
    const bool plane_grids = cache && planes_gridded(scene, voxel);
    // The render reads the tables without the cache, in rough cells without
    // bricks, and on planes without grids; otherwise each table lives only
    // while the cache, bricks and plane grids of the lights that read it
    // are filled (issue 22, the paper's section 7).
    const bool keep_tables =
        !cache || (cache_tolerance_ < 1.0f && !bricks) || (!scene.planes().empty() && !plane_grids);
    if (keep_tables && (!same_extinction || !tables_kept_ || previous != placements_)) {
      rebuilds_ += std::uint64_t(tables_.build(shadows, scene.lights(), cell, same_extinction));
    }
    tables_kept_ = keep_tables;
    if (!keep_tables && !same_extinction) tables_.clear();  // no table of the old extinction may be reused
    inputs_ = std::move(inputs);
    table_resolution_ = resolution;
    if (!bricks) refined_.clear();
    if (!plane_grids) plane_caches_.clear();
    if (!cache) {
      caches_.clear();
      built_ = true;
      return;
    }
    // The caches depend on the tables and on every parameter but the table
    // resolution (already covered by the tables). A light keeps its cache
    // while it reads a table of the same placement (from the same extinction).
    ParameterValues cache_params = params;
    cache_params.set("sat_resolution", params.table().at("sat_resolution").default_value);
    // Streamed or built, a light's table gives the same depths (to its
    // rounding): switching table_streaming rebuilds nothing.
    cache_params.set("table_streaming", params.table().at("table_streaming").default_value);
    // Without bricks the tolerance is read at render time only.
    if (!bricks) {
      cache_params.set("cache_tolerance", params.table().at("cache_tolerance").default_value);
      cache_params.set("cache_refinement", 0.0);
    }
    // A light whose size changed has a new filter (when derived): its cache
    // is rebuilt, its table is not.
    auto stale = [&](std::size_t i) {
      return i >= previous.size() || !(previous[i] == placements_[i]) || i >= previous_shapes.size() ||
             previous_shapes[i] != light_shapes_[i];
    };
    const std::string streaming = params.choice("table_streaming");
    const std::size_t lights = placements_.size();
    refined_.resize(lights);
    plane_caches_.resize(lights);
    cache_builds_.resize(lights, 0);
    caches_.set_unorm16(true);  // read by CachedFilteredVisibility in 16-bit
    rebuilds_ += std::uint64_t(caches_.update(
        lights, scene.volume().world_box(),
        visibility_cache_dims(scene.volume().dims(), float(params.number("cache_resolution"))), cache_params,
        [&](std::size_t light) { return placements_[light].kind != LightTableKind::None; }, stale,
        [&](std::size_t light, std::int64_t count, const auto& point, float* out) {
          transmittances(light, count, point, out);
        },
        [&](std::size_t light) {
          // Without kept tables: build (or keep, for a light sharing the
          // last one's CSAT) only the table this light reads, or stream it.
          if (!keep_tables) prepare_light_table(scene, shadows, cell, streaming, light);
        },
        [&](std::size_t light, const Volume& light_cache) {
          // What else reads this light's table: its bricks and plane grids.
          ++cache_builds_[light];
          if (bricks) {
            refined_[light].build(light_cache, cache_tolerance_, kProbeTolerance, refine,
                                  [&](std::int64_t count, const auto& point, float* out) {
                                    optical_depths(light, count, point, out);
                                  });
          }
          if (plane_grids) fill_plane_grids(scene, light, voxel);
        }));
    for (std::size_t i = 0; i < lights; ++i) {
      if (placements_[i].kind == LightTableKind::None) {
        refined_[i].clear();
        plane_caches_[i].clear();
      }
    }
    // Planes that moved under caches that did not: their grids need the
    // tables again (one at a time without kept tables).
    if (plane_grids) {
      const std::vector<Light>& scene_lights = scene.lights();
      for (std::size_t i = 0; i < lights; ++i) {
        if (placements_[i].kind == LightTableKind::None ||
            plane_caches_[i].current({scene_lights[i]}, scene.planes(), plane_cell(i, voxel), cache_builds_[i])) {
          continue;
        }
        if (!keep_tables) prepare_light_table(scene, shadows, cell, streaming, i);
        fill_plane_grids(scene, i, voxel);
      }
    }
    refined_views_.clear();
    if (bricks) {
      for (const RefinedCells& r : refined_) refined_views_.push_back(r.view());
    }
    plane_views_.clear();
    if (plane_grids) {
      for (const PlaneCaches& p : plane_caches_) plane_views_.push_back(p.view());
    }
    if (!keep_tables) tables_.release(placements_.size());
    stream_.reset();
    built_ = true;
  }

  void render(const Scene& scene, Image& image, RenderStats* stats) override {
    RenderView view = resources_.view(scene);
    view.structures = rebuilds_ + plane_builds_;  // the tables', caches' and plane grids' version, for device mirrors
    const Shading shading = scene.material().shading;
    const FilteredVisibility direct = visibility();
    if (caches_.built()) {
      // Without the tables every lookup reads the cache (clamped to its box).
      constexpr float kFar = std::numeric_limits<float>::max();
      for (std::size_t i = 0; i < placements_.size(); ++i) {  // CachedFilteredVisibility reads them in 16-bit
        assert(!caches_.views()[i].data || caches_.views()[i].type == VoxelType::UInt16);
      }
      const Box3 tables_box = tables_kept_ ? view.box : Box3{vec3(-kFar), vec3(kFar)};
      const CachedFilteredVisibility cached{direct, caches_.views(), tables_box, cache_tolerance_,
                                            refined_views_.empty() ? nullptr : refined_views_.data(),
                                            plane_views_.empty() ? nullptr : plane_views_.data()};
      render_lit(view, cached, shading, image, stats);
    } else {
      render_lit(view, direct, shading, image, stats);
    }
  }

  std::uint64_t aux_bytes() const override {
    std::uint64_t bytes = tables_.bytes() + caches_.bytes();
    for (const RefinedCells& r : refined_) bytes += r.bytes();
    for (const PlaneCaches& p : plane_caches_) bytes += p.bytes();
    return bytes;
  }

  // Each table build and each light's cache build count one.
  std::uint64_t rebuilds() const override { return rebuilds_; }

 private:
  // The filters (filtered_sat.h, "The filter from the light's size"): with
  // filter_voxels unset each of the first FilteredVisibility::kLightFilters
  // lights gets the filter of its size (kDefaultFilterVoxels without one),
  // the others that default; set, every light gets it. light_shapes_ keeps
  // per light (width, gaussian) for the caches' staleness.
  void derive_filters(const Scene& scene, const ParameterValues& params, float voxel) {
    const double knob = params.number("filter_voxels");
    if (knob >= 0.0 && knob < kMinFilterVoxels) {
      throw InvalidArgument("filter_voxels", "must be at least 0.25 voxels, or negative for the light's size; got " +
                                                 std::to_string(knob));
    }
    const std::string kernel = params.choice("kernel");
    const float scale = float(params.number("shadow_density_scale"));
    const float offset = float(params.number("patch_offset"));
    auto make = [&](float width, bool gaussian_light) {
      return make_shadow_filter(kernel_named(kernel, gaussian_light), width, scale, offset);
    };
    const float fallback = float(knob < 0.0 ? kDefaultFilterVoxels : knob) * voxel;
    shared_filter_ = make(fallback, false);
    filters_.clear();
    light_shapes_.clear();
    const Box3 box = scene.volume().world_box();
    for (const Light& light : scene.lights()) {
      LightFilterShape shape;
      if (knob < 0.0) shape = filter_from_light(light, box);
      const float width = shape.width > 0.0f
                              ? glm::clamp(shape.width, float(kMinFilterVoxels) * voxel, float(kMaxFilterVoxels) * voxel)
                              : fallback;
      light_shapes_.push_back(vec2(width, shape.gaussian ? 1.0f : 0.0f));
      if (filters_.size() < std::size_t(FilteredVisibility::kLightFilters)) filters_.push_back(make(width, shape.gaussian));
    }
  }
  Box3 shadow_box(const Scene& scene, std::size_t light) const {
    return filtered_shadow_box(scene.volume().world_box(), visibility().filter(int(light)), placements_[light].cell);
  }
  // Light i's plane grid spacing in world units.
  float plane_cell(std::size_t light, float voxel) const {
    return glm::clamp(light_shapes_[light].x / kPlaneNodesPerFilter, kMinPlaneNodeVoxels * voxel,
                      kMaxPlaneNodeVoxels * voxel);
  }
  // Whether every light with a table gets a grid on every plane.
  bool planes_gridded(const Scene& scene, float voxel) const {
    for (std::size_t i = 0; i < placements_.size(); ++i) {
      if (placements_[i].kind == LightTableKind::None) continue;
      for (const Plane& plane : scene.planes()) {
        if (!PlaneCaches::covers(scene.lights()[i], plane, shadow_box(scene, i), plane_cell(i, voxel))) return false;
      }
    }
    return true;
  }
  // Light i's grids on the planes, from its table (which must live) or its stream.
  void fill_plane_grids(const Scene& scene, std::size_t light, float voxel) {
    plane_builds_ += std::uint64_t(plane_caches_[light].update(
        {scene.lights()[light]}, scene.planes(), shadow_box(scene, light), plane_cell(light, voxel),
        cache_builds_[light], [&](int, std::int64_t count, const auto& point, float* out) {
          transmittances(light, count, point, out);
        }));
  }
  // Without kept tables, before light i's cache, bricks or grids: its table
  // alone (LightTables::build's only_light), or where table_streaming takes
  // it, no table but a stream of its layers.
  void prepare_light_table(const Scene& scene, const RenderView& shadows, float cell, const std::string& streaming,
                           std::size_t light) {
    stream_.reset();
    if (streaming != "off" && placements_[light].kind != LightTableKind::None) {
      const LightTableLookup lookup =
          LightTables::lookup_without_table(shadows.box, scene.lights(), cell, int(light));
      const ivec3 n = (lookup.kind == LightTableKind::Cartesian ? lookup.cartesian.cells : lookup.spherical.cells) + 1;
      const std::uint64_t table_bytes = std::uint64_t(n.x) * std::uint64_t(n.y) * std::uint64_t(n.z) * sizeof(float);
      if (streaming == "on" || table_bytes > kStreamTablesAbove) {
        tables_.release(placements_.size());
        stream_.emplace(shadows, lookup, extinction_samples_per_axis(cell / shadows.volume.min_spacing()));
        ++rebuilds_;
        return;
      }
    }
    rebuilds_ += std::uint64_t(tables_.build(shadows, scene.lights(), cell, true, int(light)));
  }
  // Light i's filtered optical depths (with the density scale) at a batch
  // of points, from its stream or its table.
  template <class Point>
  void optical_depths(std::size_t light, std::int64_t count, const Point& point, float* out) const {
    const FilteredVisibility direct = visibility();
    if (stream_) {
      const ShadowFilter& filter = direct.filter(int(light));
      stream_->depths(filter, count, point, out);
      parallel_for(0, count, [&](std::int64_t first, std::int64_t last) {
        for (std::int64_t i = first; i < last; ++i) out[i] *= filter.density_scale;
      });
      return;
    }
    parallel_for(0, count, [&](std::int64_t first, std::int64_t last) {
      for (std::int64_t i = first; i < last; ++i) out[i] = direct.optical_depth(int(light), point(i));
    });
  }
  template <class Point>
  void transmittances(std::size_t light, std::int64_t count, const Point& point, float* out) const {
    optical_depths(light, count, point, out);
    parallel_for(0, count, [&](std::int64_t first, std::int64_t last) {
      for (std::int64_t i = first; i < last; ++i) out[i] = exp_nonpositive(-out[i]);
    });
  }
  FilteredVisibility visibility() const {
    return FilteredVisibility::with(tables_.lookups().data(), filters_, shared_filter_);
  }

  SceneResources resources_;
  std::vector<ShadowFilter> filters_;  // per light, the first kLightFilters
  ShadowFilter shared_filter_;         // the lights beyond them
  std::vector<vec2> light_shapes_;     // per light: filter width (world) and gaussian (1) or box (0)
  LightTables tables_;
  std::optional<StreamedLightTable> stream_;  // during a prepare: the streamed table of the light being filled
  bool built_ = false;        // the last prepare finished
  bool tables_kept_ = false;  // tables_ holds every light's table (else none)
  ExtinctionInputs inputs_;   // what the tables and caches were built from
  std::vector<LightTables::Placement> placements_;  // per light: the table it read in the last prepare
  double table_resolution_ = 0.0;
  LightVisibilityCaches caches_;  // one per light with a table
  std::vector<RefinedCells> refined_;  // per light: its cache's rough cells, refined
  std::vector<RefinedCellsView> refined_views_;  // per light; empty without bricks
  std::vector<PlaneCaches> plane_caches_;        // per light: its grids on the planes
  std::vector<PlaneCachesView> plane_views_;     // per light; empty without plane grids
  std::vector<std::uint64_t> cache_builds_;      // per light: its cache builds, the plane grids' version
  std::uint64_t plane_builds_ = 0;
  float cache_tolerance_ = 1.0f;
  std::uint64_t rebuilds_ = 0;
};

}  // namespace

TechniqueInfo filtered_sat_info() {
  return TechniqueInfo{
      "filtered-sat",
      "low-pass filtered soft shadows from light-aligned summed-area tables (Ament et al. 2014)",
      ParameterTable{{
          ParameterSpec::real("filter_voxels", -1.0, -1.0, kMaxFilterVoxels,
                              "shadow filter width in voxels (softness; the cost does not depend on it; < 0 = "
                              "from each light's size, 5 for directional and point lights)"),
          ParameterSpec::choice("kernel", "auto", {"auto", "box", "gaussian"},
                                "box (constant time) or gaussian (8x8 sub-cuboids, same variance as the box); "
                                "auto = gaussian for a gaussian distant light's derived filter, box otherwise"),
          ParameterSpec::real("patch_offset", 0.0, 0.0, 4.0,
                              "start the filtered volume this many filter half-widths toward the light "
                              "(0 = at the sample, the paper; > 0 lessens lit surfaces' self-shadowing)"),
          ParameterSpec::real("sat_resolution", 1.0, 0.1, 2.0,
                              "summed-area table cells per voxel along each axis (paper: 0.5)"),
          ParameterSpec::flag("shadow_cache", true,
                              "store each light's transmittance on a grid instead of reading the tables per sample"),
          ParameterSpec::real("cache_resolution", 0.5, 0.05, 2.0,
                              "shadow cache grid size as a fraction of the data grid"),
          ParameterSpec::real("cache_tolerance", 0.01, 0.0, 1.0,
                              "cache cells whose texels differ by more than this read their brick, a finer grid "
                              "built with the cache (0 = the tables per sample, 1 = the cache everywhere); each "
                              "light's table is released once its cache, bricks and floor grids are filled"),
          ParameterSpec::integer("cache_refinement", 6, 0, 8,
                                 "samples per cache cell edge in the finest bricks of rough cells; each cell gets "
                                 "the coarsest of 2, 4, ... up to this that reads the tables well (0 = the tables "
                                 "per sample there, kept for the whole render; 1 is refused)"),
          ParameterSpec::choice("table_streaming", "auto", {"auto", "on", "off"},
                                "without kept tables, evaluate a light's cache, bricks and floor grids layer by "
                                "layer along the light instead of building its whole table (memory of two table "
                                "layers, time of three or four table builds); auto = for tables over 512 MiB"),
          ParameterSpec::real("shadow_density_scale", 1.0, 0.0, 100.0,
                              "multiplies the filtered optical depth (0 = unshadowed)"),
      }},
      [] { return std::make_unique<FilteredSat>(); }};
}

}  // namespace penumbra

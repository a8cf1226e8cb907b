#include "penumbra/techniques/filtered_sat/filtered_sat.h"

#include "penumbra/render/render_lit.h"
#include "penumbra/render/scene_resources.h"
#include "penumbra/techniques/filtered_sat/filtered_visibility.h"
#include "penumbra/techniques/sat_common/table_dependencies.h"
#include "penumbra/techniques/sat_common/visibility_cache.h"

#include <vector>

namespace penumbra {
namespace {

FilterKernel kernel_named(const std::string& name) {
  return name == "gaussian" ? FilterKernel::Gaussian : FilterKernel::Box;
}

class FilteredSat final : public Technique {
 public:
  void prepare(const Scene& scene, const ParameterValues& params) override {
    resources_.update(scene);
    const float voxel = scene.volume().view().min_spacing();
    filter_ = make_shadow_filter(kernel_named(params.choice("kernel")), float(params.number("filter_voxels")) * voxel,
                                 float(params.number("shadow_density_scale")),
                                 float(params.number("patch_offset")));
    // The tables depend on the extinction (data, shadow TF, clip planes), the
    // resolution and each light's direction or position; a light's colour
    // or intensity, a floor plane or a render-only TF edit change none.
    const RenderView shadows = resources_.shadow_view(scene);
    ExtinctionInputs inputs = extinction_inputs(scene, shadows);
    std::vector<LightPlacement> placements = light_placements(scene.lights());
    const double resolution = params.number("sat_resolution");
    const bool same_extinction = tables_built_ && inputs == inputs_ && resolution == table_resolution_;
    if (!same_extinction || placements != placements_) {
      tables_built_ = false;
      if (!same_extinction) caches_.clear();
      rebuilds_ += std::uint64_t(tables_.build(shadows, scene.lights(), voxel / float(resolution), same_extinction));
      tables_built_ = true;
      inputs_ = std::move(inputs);
      table_resolution_ = resolution;
    }
    std::vector<std::uint64_t> previous_ids = std::move(cached_table_ids_);
    std::vector<LightPlacement> previous_placements = std::move(placements_);
    placements_ = std::move(placements);
    cached_table_ids_ = tables_.table_ids();
    if (!params.flag("shadow_cache")) {
      caches_.clear();
      return;
    }
    // The caches depend on the tables and on every parameter but the table
    // resolution (already covered by the tables). A light keeps its cache
    // while it reads the same table from the same place.
    ParameterValues cache_params = params;
    cache_params.set("sat_resolution", params.table().at("sat_resolution").default_value);
    cache_params.set("cache_tolerance", params.table().at("cache_tolerance").default_value);  // read-time only
    cache_tolerance_ = float(params.number("cache_tolerance"));
    auto stale = [&](std::size_t i) {
      return i >= previous_ids.size() || previous_ids[i] != cached_table_ids_[i] ||
             !(previous_placements[i] == placements_[i]);
    };
    const FilteredVisibility direct{tables_.lookups().data(), filter_};
    rebuilds_ += std::uint64_t(caches_.update(
        tables_.lookups().size(), scene.volume().world_box(),
        visibility_cache_dims(scene.volume().dims(), float(params.number("cache_resolution"))), cache_params,
        [&](std::size_t light) { return tables_.lookups()[light].kind != LightTableKind::None; }, stale,
        [&](std::size_t light, vec3 p) { return direct.transmittance(int(light), p); }));
  }

  void render(const Scene& scene, Image& image, RenderStats* stats) override {
    RenderView view = resources_.view(scene);
    view.structures = rebuilds_;  // the tables' and caches' version, for device mirrors
    const Shading shading = scene.material().shading;
    const FilteredVisibility direct{tables_.lookups().data(), filter_};
    if (caches_.built()) {
      const CachedFilteredVisibility cached{direct, caches_.views(), view.box, cache_tolerance_};
      render_lit(view, cached, shading, image, stats);
    } else {
      render_lit(view, direct, shading, image, stats);
    }
  }

  std::uint64_t aux_bytes() const override { return tables_.bytes() + caches_.bytes(); }

  // Each table build and each light's cache build count one.
  std::uint64_t rebuilds() const override { return rebuilds_; }

 private:
  SceneResources resources_;
  ShadowFilter filter_;
  LightTables tables_;
  bool tables_built_ = false;
  ExtinctionInputs inputs_;                   // what the tables were built from
  std::vector<LightPlacement> placements_;    // the lights of the last prepare
  std::vector<std::uint64_t> cached_table_ids_;  // the table each light read then
  double table_resolution_ = 0.0;
  LightVisibilityCaches caches_;  // one per light with a table
  float cache_tolerance_ = 1.0f;
  std::uint64_t rebuilds_ = 0;
};

}  // namespace

TechniqueInfo filtered_sat_info() {
  return TechniqueInfo{
      "filtered-sat",
      "low-pass filtered soft shadows from light-aligned summed-area tables (Ament et al. 2014)",
      ParameterTable{{
          ParameterSpec::real("filter_voxels", 5.0, 0.25, 256.0,
                              "shadow filter width in voxels (softness; the cost does not depend on it)"),
          ParameterSpec::choice("kernel", "box", {"box", "gaussian"},
                                "box (constant time) or gaussian (8x8 sub-cuboids, same variance as the box)"),
          ParameterSpec::real("patch_offset", 0.0, 0.0, 4.0,
                              "start the filtered volume this many filter half-widths toward the light "
                              "(0 = at the sample, the paper; > 0 lessens lit surfaces' self-shadowing)"),
          ParameterSpec::real("sat_resolution", 1.0, 0.1, 2.0,
                              "summed-area table cells per voxel along each axis (paper: 0.5)"),
          ParameterSpec::flag("shadow_cache", true,
                              "store each light's transmittance on a grid instead of reading the tables per sample"),
          ParameterSpec::real("cache_resolution", 0.5, 0.05, 2.0,
                              "shadow cache grid size as a fraction of the data grid"),
          ParameterSpec::real("cache_tolerance", 0.1, 0.0, 1.0,
                              "cache cells whose texels differ by more than this read the tables instead "
                              "(1 = always the cache)"),
          ParameterSpec::real("shadow_density_scale", 1.0, 0.0, 100.0,
                              "multiplies the filtered optical depth (0 = unshadowed)"),
      }},
      [] { return std::make_unique<FilteredSat>(); }};
}

}  // namespace penumbra

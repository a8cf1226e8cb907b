#include "penumbra/techniques/filtered_sat/filtered_sat.h"

#include "penumbra/render/render_lit.h"
#include "penumbra/render/scene_resources.h"
#include "penumbra/techniques/filtered_sat/filtered_visibility.h"
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
    const bool shared_changed = resources_.update(scene);
    const float voxel = scene.volume().view().min_spacing();
    filter_ = make_shadow_filter(kernel_named(params.choice("kernel")), float(params.number("filter_voxels")) * voxel,
                                 float(params.number("shadow_density_scale")));
    const double resolution = params.number("sat_resolution");
    const SceneVersions& v = scene.versions();
    const bool tables_stale = shared_changed || !tables_built_ || v.lights != lights_version_ ||
                              v.geometry != geometry_version_ || resolution != table_resolution_;
    if (tables_stale) {
      tables_built_ = false;
      caches_.clear();
      tables_.build(resources_.shadow_view(scene), scene.lights(), voxel / float(resolution));
      tables_built_ = true;
      lights_version_ = v.lights;
      geometry_version_ = v.geometry;
      table_resolution_ = resolution;
      ++rebuilds_;
    }
    if (!params.flag("shadow_cache")) {
      caches_.clear();
      return;
    }
    // The caches depend on the tables and on every parameter but the table
    // resolution (already covered by tables_stale).
    ParameterValues cache_params = params;
    cache_params.set("sat_resolution", params.table().at("sat_resolution").default_value);
    if (!tables_stale && caches_.current(cache_params)) return;
    const FilteredVisibility direct{tables_.lookups().data(), filter_};
    caches_.build(
        tables_.lookups().size(), scene.volume().world_box(),
        visibility_cache_dims(scene.volume().dims(), float(params.number("cache_resolution"))), cache_params,
        [&](std::size_t light) { return tables_.lookups()[light].kind != LightTableKind::None; },
        [&](std::size_t light, vec3 p) { return direct.transmittance(int(light), p); });
    ++rebuilds_;
  }

  void render(const Scene& scene, Image& image, RenderStats* stats) override {
    const RenderView view = resources_.view(scene);
    const Shading shading = scene.material().shading;
    const FilteredVisibility direct{tables_.lookups().data(), filter_};
    if (caches_.built()) {
      const CachedFilteredVisibility cached{direct, caches_.views(), view.box};
      render_lit(view, cached, shading, image, stats);
    } else {
      render_lit(view, direct, shading, image, stats);
    }
  }

  std::uint64_t aux_bytes() const override { return tables_.bytes() + caches_.bytes(); }

  // Table builds and cache builds count one each.
  std::uint64_t rebuilds() const override { return rebuilds_; }

 private:
  SceneResources resources_;
  ShadowFilter filter_;
  LightTables tables_;
  bool tables_built_ = false;
  std::uint64_t lights_version_ = 0;
  std::uint64_t geometry_version_ = 0;
  double table_resolution_ = 0.0;
  LightVisibilityCaches caches_;  // one per light with a table
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
          ParameterSpec::real("sat_resolution", 1.0, 0.1, 2.0,
                              "summed-area table cells per voxel along each axis (paper: 0.5)"),
          ParameterSpec::flag("shadow_cache", true,
                              "store each light's transmittance on a grid instead of reading the tables per sample"),
          ParameterSpec::real("cache_resolution", 0.5, 0.05, 2.0,
                              "shadow cache grid size as a fraction of the data grid"),
          ParameterSpec::real("shadow_density_scale", 1.0, 0.0, 100.0,
                              "multiplies the filtered optical depth (0 = unshadowed)"),
      }},
      [] { return std::make_unique<FilteredSat>(); }};
}

}  // namespace penumbra

#include "penumbra/techniques/cone_shadows/cone_shadows.h"

#include "penumbra/render/render_lit.h"
#include "penumbra/render/scene_resources.h"
#include "penumbra/techniques/cone_shadows/cone_march.h"
#include "penumbra/techniques/sat_common/table_dependencies.h"
#include "penumbra/techniques/sat_common/visibility_cache.h"
#include "penumbra/techniques/sat_common/volume_aligned_table.h"

#include <vector>

namespace penumbra {
namespace {

class ConeShadows final : public Technique {
 public:
  void prepare(const Scene& scene, const ParameterValues& params) override {
    resources_.update(scene);
    const bool table_rebuilt = table_.update(scene, resources_, params.number("sat_resolution"));
    if (table_rebuilt) {
      caches_.clear();
      ++rebuilds_;
    }
    const float voxel = scene.volume().view().min_spacing();
    cone_ = ConeMarch{table_.view(),
                      table_.grid(),
                      scene.volume().world_box(),
                      float(std::tan(glm::radians(params.number("cone_angle_deg")))),
                      float(params.number("step_voxels")) * voxel,
                      float(params.number("shadow_density_scale"))};
    if (!params.flag("shadow_cache")) {
      caches_.clear();
      return;
    }
    ParameterValues cache_params = params;
    cache_params.set("sat_resolution", params.table().at("sat_resolution").default_value);
    // A light's colour or intensity does not change its transmittance: a
    // light's cache is rebuilt when it moves (or the table or parameters
    // change), the others are kept.
    std::vector<LightPlacement> placements = light_placements(scene.lights());
    if (caches_.current(cache_params) && placements == placements_) return;
    const std::vector<Light>& lights = scene.lights();
    const ConeMarch cone = cone_;
    rebuilds_ += std::uint64_t(caches_.update(
        lights.size(), cone.box, visibility_cache_dims(scene.volume().dims(), float(params.number("cache_resolution"))),
        cache_params, [&](std::size_t i) { return lights[i].type != LightType::Environment; },
        [&](std::size_t i) { return i >= placements_.size() || !(placements[i] == placements_[i]); },
        [&](std::size_t i, vec3 p) { return cone.transmittance(p, sample_light(lights[i], p)); }));
    placements_ = std::move(placements);
  }

  void render(const Scene& scene, Image& image, RenderStats* stats) override {
    RenderView view = resources_.view(scene);
    view.structures = rebuilds_;  // the tables' and caches' version, for device mirrors
    const Shading shading = scene.material().shading;
    if (caches_.built()) {
      const CachedConeMarch cached{cone_, caches_.views()};
      render_lit(view, cached, shading, image, stats);
    } else {
      render_lit(view, cone_, shading, image, stats);
    }
  }

  std::uint64_t aux_bytes() const override { return table_.bytes() + caches_.bytes(); }
  // The table build and each light's cache build count one each.
  std::uint64_t rebuilds() const override { return rebuilds_; }

 private:
  SceneResources resources_;
  VolumeAlignedTable table_{"cone-shadows summed-area table"};
  ConeMarch cone_;
  LightVisibilityCaches caches_;
  std::vector<LightPlacement> placements_;  // what the caches were built for
  std::uint64_t rebuilds_ = 0;
};

}  // namespace

TechniqueInfo cone_shadows_info() {
  return TechniqueInfo{
      "cone-shadows",
      "soft shadows from cones of growing cubes in a volume-aligned SAT (Schlegel et al. 2011)",
      ParameterTable{{
          ParameterSpec::real("cone_angle_deg", 5.0, 0.0, 45.0, "half-angle of the shadow cone in degrees"),
          ParameterSpec::real("step_voxels", 4.0, 0.5, 64.0, "cone step length in voxels"),
          ParameterSpec::real("sat_resolution", 1.0, 0.1, 2.0, "summed-area table cells per voxel along each axis"),
          ParameterSpec::flag("shadow_cache", true, "store each light's transmittance on a grid instead of marching cones per sample"),
          ParameterSpec::real("cache_resolution", 0.5, 0.05, 2.0, "shadow cache grid size as a fraction of the data grid"),
          ParameterSpec::real("shadow_density_scale", 1.0, 0.0, 100.0, "multiplies the optical depth (0 = unshadowed)"),
      }},
      [] { return std::make_unique<ConeShadows>(); }};
}

}  // namespace penumbra

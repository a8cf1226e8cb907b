#include "penumbra/techniques/cone_shadows/cone_shadows.h"

#include "penumbra/render/render_lit.h"
#include "penumbra/render/scene_resources.h"
#include "penumbra/techniques/cone_shadows/cone_march.h"
#include "penumbra/techniques/sat_common/visibility_cache.h"
#include "penumbra/techniques/sat_common/volume_aligned_table.h"

#include <vector>

namespace penumbra {
namespace {

class ConeShadows final : public Technique {
 public:
  void prepare(const Scene& scene, const ParameterValues& params) override {
    const bool shared_changed = resources_.update(scene);
    const bool table_rebuilt = table_.update(scene, resources_, shared_changed, params.number("sat_resolution"));
    if (table_rebuilt) {
      clear_caches();
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
      clear_caches();
      return;
    }
    ParameterValues cache_params = params;
    cache_params.set("sat_resolution", params.table().at("sat_resolution").default_value);
    if (caches_built_ && cache_params == cache_params_ && scene.versions().lights == lights_version_) return;
    clear_caches();
    const ivec3 dims = visibility_cache_dims(scene.volume().dims(), float(params.number("cache_resolution")));
    const ConeMarch cone = cone_;
    cache_views_.assign(scene.lights().size(), VolumeView{});
    for (std::size_t i = 0; i < scene.lights().size(); ++i) {
      const Light& light = scene.lights()[i];
      if (light.type == LightType::Environment) continue;
      caches_.push_back(build_visibility_cache(cone.box, dims, [&](vec3 p) {
        return cone.transmittance(p, sample_light(light, p));
      }));
      cache_views_[i] = caches_.back().view();
    }
    caches_built_ = true;
    cache_params_ = cache_params;
    lights_version_ = scene.versions().lights;
    ++rebuilds_;
  }

  void render(const Scene& scene, Image& image, RenderStats* stats) override {
    const RenderView view = resources_.view(scene);
    const Shading shading = scene.material().shading;
    if (caches_built_) {
      const CachedConeMarch cached{cone_, cache_views_.data()};
      render_lit(view, cached, shading, image, stats);
    } else {
      render_lit(view, cone_, shading, image, stats);
    }
  }

  std::uint64_t aux_bytes() const override {
    std::uint64_t bytes = table_.bytes();
    for (const Volume& c : caches_) bytes += c.total_bytes();
    return bytes;
  }
  // Table builds and cache builds count one each.
  std::uint64_t rebuilds() const override { return rebuilds_; }

 private:
  void clear_caches() {
    caches_.clear();
    cache_views_.clear();
    caches_built_ = false;
  }

  SceneResources resources_;
  VolumeAlignedTable table_{"cone-shadows summed-area table"};
  ConeMarch cone_;
  std::vector<Volume> caches_;
  std::vector<VolumeView> cache_views_;  // one per light
  bool caches_built_ = false;
  ParameterValues cache_params_;
  std::uint64_t lights_version_ = 0;
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

#include "penumbra/techniques/sat_ao/sat_ao.h"

#include "penumbra/render/render_lit.h"
#include "penumbra/render/scene_resources.h"
#include "penumbra/techniques/sat_ao/ambient_occlusion.h"
#include "penumbra/techniques/sat_common/visibility_cache.h"
#include "penumbra/techniques/sat_common/volume_aligned_table.h"

#include <optional>

namespace penumbra {
namespace {

class SatAo final : public Technique {
 public:
  void prepare(const Scene& scene, const ParameterValues& params) override {
    resources_.update(scene);
    const bool table_rebuilt = table_.update(scene, resources_, params.number("sat_resolution"));
    if (table_rebuilt) {
      cache_.reset();
      ++rebuilds_;
    }
    const float voxel = scene.volume().view().min_spacing();
    occlusion_ = AmbientOcclusion{table_.view(), table_.grid(), float(params.number("radius_voxels")) * voxel,
                                  float(params.number("shadow_density_scale"))};
    if (!params.flag("shadow_cache")) {
      cache_.reset();
      return;
    }
    ParameterValues cache_params = params;
    cache_params.set("sat_resolution", params.table().at("sat_resolution").default_value);
    if (cache_ && cache_params == cache_params_) return;
    cache_.reset();
    const AmbientOcclusion ao = occlusion_;
    cache_.emplace(build_visibility_cache(scene.volume().world_box(),
                                          visibility_cache_dims(scene.volume().dims(),
                                                                float(params.number("cache_resolution"))),
                                          [&](vec3 p) { return ao.occlusion(p); }));
    cache_params_ = cache_params;
    ++rebuilds_;
  }

  void render(const Scene& scene, Image& image, RenderStats* stats) override {
    RenderView view = resources_.view(scene);
    view.structures = rebuilds_;  // the tables' and caches' version, for device mirrors
    const Shading shading = scene.material().shading;
    if (cache_) {
      const CachedAmbientOcclusion cached{occlusion_, cache_->view(), view.box};
      render_lit(view, cached, shading, image, stats);
    } else {
      render_lit(view, occlusion_, shading, image, stats);
    }
  }

  std::uint64_t aux_bytes() const override { return table_.bytes() + (cache_ ? cache_->total_bytes() : 0); }
  // Table builds and cache builds count one each.
  std::uint64_t rebuilds() const override { return rebuilds_; }

 private:
  SceneResources resources_;
  VolumeAlignedTable table_{"sat-ao summed-area table"};
  AmbientOcclusion occlusion_;
  std::optional<Volume> cache_;
  ParameterValues cache_params_;
  std::uint64_t rebuilds_ = 0;
};

}  // namespace

TechniqueInfo sat_ao_info() {
  return TechniqueInfo{
      "sat-ao",
      "ambient occlusion from the mean extinction around each sample, volume-aligned SAT (Schlegel et al. 2011)",
      ParameterTable{{
          ParameterSpec::real("radius_voxels", 4.0, 0.5, 128.0, "occlusion radius R in voxels"),
          ParameterSpec::real("sat_resolution", 1.0, 0.1, 2.0, "summed-area table cells per voxel along each axis"),
          ParameterSpec::flag("shadow_cache", true, "store the occlusion on a grid instead of reading the table per sample"),
          ParameterSpec::real("cache_resolution", 0.5, 0.05, 2.0, "occlusion grid size as a fraction of the data grid"),
          ParameterSpec::real("shadow_density_scale", 1.0, 0.0, 100.0, "multiplies the mean extinction (0 = no occlusion)"),
      }},
      [] { return std::make_unique<SatAo>(); }};
}

}  // namespace penumbra

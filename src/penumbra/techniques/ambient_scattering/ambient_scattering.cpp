#include "penumbra/techniques/ambient_scattering/ambient_scattering.h"

#include "penumbra/base/error.h"
#include "penumbra/render/render_lit.h"
#include "penumbra/render/scene_resources.h"
#include "penumbra/techniques/ambient_scattering/ambient_tube.h"
#include "penumbra/techniques/filtered_sat/shadow_filter.h"
#include "penumbra/techniques/sat_common/table_dependencies.h"
#include "penumbra/techniques/sat_common/visibility_cache.h"
#include "penumbra/techniques/sat_common/volume_aligned_table.h"

#include <fmt/format.h>

#include <optional>
#include <vector>

namespace penumbra {
namespace {

// The paper's radius for Fig. 8(c), for lights without a size.
constexpr double kDefaultRadiusVoxels = 8.0;
// Below half a voxel the tube's steps outnumber the voxels along it.
constexpr double kMinRadiusVoxels = 0.5;

// R in world units: the parameter, or the radius whose cube (2R wide) is as
// wide as the widest filter derived from the lights' sizes.
float ambient_radius(const Scene& scene, const ParameterValues& params) {
  const float voxel = scene.volume().view().min_spacing();
  const double radius = params.number("radius_voxels");
  if (radius >= 0.0 && radius < kMinRadiusVoxels) {
    throw InvalidArgument("radius_voxels", fmt::format("{} is neither < 0 (from the lights) nor >= {}", radius,
                                                       kMinRadiusVoxels));
  }
  if (radius > 0.0) return float(radius) * voxel;
  float width = 0.0f;
  for (const Light& l : scene.lights()) width = glm::max(width, filter_from_light(l, scene.volume().world_box()).width);
  if (!(width > 0.0f)) return float(kDefaultRadiusVoxels) * voxel;
  return glm::max(0.5f * width, float(kMinRadiusVoxels) * voxel);
}

class AmbientScattering final : public Technique {
 public:
  void prepare(const Scene& scene, const ParameterValues& params) override {
    resources_.update(scene);
    const ScatteringModel model{float(params.number("scattering_albedo")), scene.material().phase_g,
                                params.integer("preintegration_paths")};
    const bool new_scattering = !scattering_ || !(scattering_->model() == model);
    if (new_scattering) {
      scattering_ = preintegrated_scattering(model);
      ++scattering_version_;
    }
    const bool table_rebuilt = table_.update(scene, resources_, params.number("sat_resolution"));
    if (table_rebuilt) ++rebuilds_;
    const float radius = ambient_radius(scene, params);
    const float density = float(params.number("shadow_density_scale"));
    // What the caches read besides the lights: a change rebuilds them all.
    const std::vector<double> inputs{double(radius), double(density), params.number("cache_resolution"),
                                     double(scattering_version_)};
    if (table_rebuilt || inputs != inputs_ || !params.flag("shadow_cache")) {
      tubes_.clear();
      radii_.reset();
      plane_caches_.clear();
    }
    inputs_ = inputs;
    tube_ = AmbientTube{table_.view(),     table_.grid(), scene.volume().world_box(), radius, density,
                        scattering_->view(), CameraView{}};
    if (!params.flag("shadow_cache")) return;

    const AmbientTube tube = tube_;
    const Box3 box = tube.box;
    const ivec3 dims = visibility_cache_dims(scene.volume().dims(), float(params.number("cache_resolution")));
    if (!radii_) {
      radii_.emplace(build_visibility_cache(box, dims, [&](vec3 p) { return tube.optical_radius(p); }));
      ++rebuilds_;
    }
    // A light's colour or intensity does not change its tube: a light's
    // cache is rebuilt when it moves, the others are kept.
    std::vector<LightPlacement> placements = light_placements(scene.lights());
    const std::vector<Light>& lights = scene.lights();
    if (!tubes_.built() || placements != placements_) {
      rebuilds_ += std::uint64_t(tubes_.update(
          lights.size(), box, dims, ParameterValues(),
          [&](std::size_t i) { return lights[i].type != LightType::Environment; },
          [&](std::size_t i) { return i >= placements_.size() || !(placements[i] == placements_[i]); },
          [&](std::size_t i, vec3 p) {
            const LightSample ls = sample_light(lights[i], p);
            return tube.tube_transfer(p, ls.to_light, ls.distance);
          }));
      placements_ = std::move(placements);
    }
    // The planes' caches follow the tube caches and the planes; a sphere's
    // reach beyond the box widens the region the tubes can shadow.
    const Box3 reach{box.lower - vec3(radius), box.upper + vec3(radius)};
    plane_builds_ += std::uint64_t(plane_caches_.update(
        lights, scene.planes(), reach, scene.volume().view().min_spacing(), rebuilds_,
        [&](int i, vec3 p) { return tube.plane(i, 0, p, sample_light(lights[std::size_t(i)], p)).x; }));
  }

  void render(const Scene& scene, Image& image, RenderStats* stats) override {
    RenderView view = resources_.view(scene);
    // The tables' and caches' version, for device mirrors.
    view.structures = rebuilds_ + plane_builds_ + scattering_version_;
    AmbientTube tube = tube_;
    tube.camera = view.camera;
    const Shading shading = scene.material().shading;
    if (radii_) {
      const CachedAmbientTube cached{tube, tubes_.views(), radii_->view(), plane_caches_.view()};
      render_lit(view, cached, shading, image, stats);
    } else {
      render_lit(view, tube, shading, image, stats);
    }
  }

  std::uint64_t aux_bytes() const override {
    return table_.bytes() + tubes_.bytes() + (radii_ ? radii_->total_bytes() : 0) + plane_caches_.bytes() +
           (scattering_ ? scattering_->bytes() : 0);
  }
  // The SAT build, the optical-radius grid and each light's tube cache count
  // one each.
  std::uint64_t rebuilds() const override { return rebuilds_; }

 private:
  SceneResources resources_;
  VolumeAlignedTable table_{"ambient-scattering summed-area table"};
  std::shared_ptr<const ScatteringTable> scattering_;
  std::uint64_t scattering_version_ = 0;
  AmbientTube tube_;
  std::vector<double> inputs_;
  std::optional<Volume> radii_;
  LightVisibilityCaches tubes_;
  std::vector<LightPlacement> placements_;  // what the tube caches were built for
  PlaneCaches plane_caches_;
  std::uint64_t rebuilds_ = 0;
  std::uint64_t plane_builds_ = 0;
};

}  // namespace

TechniqueInfo ambient_scattering_info() {
  return TechniqueInfo{
      "ambient-scattering",
      "soft shadows along a tube of spheres with preintegrated ambient scattering, volume-aligned SAT (Ament et "
      "al. 2013)",
      ParameterTable{{
          ParameterSpec::real("radius_voxels", -1.0, -1.0, 64.0,
                              "ambient sphere radius R in voxels, at least 0.5; tube steps are 2R (< 0 = from the "
                              "lights' sizes; 8 for directional and point lights)"),
          ParameterSpec::real("scattering_albedo", 0.6, 0.0, 0.95,
                              "albedo of the preintegrated scattering in each sphere (0 = extinction only)"),
          ParameterSpec::integer("preintegration_paths", 512, 16, 65536,
                                 "Monte Carlo paths per node of the preintegrated scattering table"),
          ParameterSpec::real("sat_resolution", 0.5, 0.1, 2.0, "summed-area table cells per voxel along each axis"),
          ParameterSpec::flag("shadow_cache", true,
                              "store each light's tube transfer on a grid instead of marching the tube per sample"),
          ParameterSpec::real("cache_resolution", 0.5, 0.05, 2.0,
                              "shadow cache grid size as a fraction of the data grid"),
          ParameterSpec::real("shadow_density_scale", 1.0, 0.0, 100.0,
                              "multiplies the spheres' extinction (0 = unshadowed)"),
      }},
      [] { return std::make_unique<AmbientScattering>(); }};
}

}  // namespace penumbra

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

// The cone of lights without a size (directional, point), and of every light
// with cone_angle_deg unset before issue 18.
constexpr double kDefaultConeAngleDeg = 5.0;

// The per-light cones derived from the lights' sizes (cone_shadows.h).
void derive_cones(const std::vector<Light>& lights, ConeMarch& cone) {
  for (std::size_t i = 0; i < lights.size() && i < std::size_t(ConeMarch::kDerivedLights); ++i) {
    const Light& l = lights[i];
    if (l.type == LightType::Distant) {
      const float x = glm::tan(glm::radians(glm::min(l.angle_deg, 89.0f)));
      const float y = glm::tan(glm::radians(glm::min(l.spread_y_deg(), 89.0f)));
      const float rms = glm::sqrt(0.5f * (x * x + y * y));
      // A uniform cone is its own cone; a Gaussian of spread tan(sigma) the
      // uniform disk of the same variance (radius 2 tan(sigma)).
      cone.light_tan[i] = l.profile == LightProfile::Uniform ? x : 2.0f * rms;
    } else if ((l.type == LightType::Sphere || l.type == LightType::Disk) && l.radius > 0.0f) {
      cone.light_radius[i] = l.radius;
    }
  }
}

class ConeShadows final : public Technique {
 public:
  void prepare(const Scene& scene, const ParameterValues& params) override {
    resources_.update(scene);
    const bool table_rebuilt = table_.update(scene, resources_, params.number("sat_resolution"));
    if (table_rebuilt) {
      caches_.clear();
      plane_caches_.clear();
      ++rebuilds_;
    }
    const float voxel = scene.volume().view().min_spacing();
    const double angle = params.number("cone_angle_deg");
    cone_ = ConeMarch{table_.view(),
                      table_.grid(),
                      scene.volume().world_box(),
                      float(std::tan(glm::radians(angle < 0.0 ? kDefaultConeAngleDeg : angle))),
                      float(params.number("step_voxels")) * voxel,
                      float(params.number("shadow_density_scale"))};
    const bool derived = angle < 0.0;
    if (derived) derive_cones(scene.lights(), cone_);
    if (!params.flag("shadow_cache")) {
      caches_.clear();
      plane_caches_.clear();
      return;
    }
    ParameterValues cache_params = params;
    cache_params.set("sat_resolution", params.table().at("sat_resolution").default_value);
    // A light's colour or intensity does not change its transmittance: a
    // light's cache is rebuilt when it moves (or the table or parameters
    // change), the others are kept.
    std::vector<LightPlacement> placements = light_placements(scene.lights());
    // With derived cones a light's size is part of its cone: a change of it
    // rebuilds that light's cache like a move.
    std::vector<vec4> sizes;
    for (const Light& l : scene.lights()) {
      sizes.push_back(derived ? vec4(l.angle_deg, l.spread_y_deg(), l.radius, float(l.profile)) : vec4(0.0f));
    }
    const std::vector<Light>& lights = scene.lights();
    const ConeMarch cone = cone_;
    if (!(caches_.current(cache_params) && placements == placements_ && sizes == sizes_)) {
      rebuilds_ += std::uint64_t(caches_.update(
        lights.size(), cone.box, visibility_cache_dims(scene.volume().dims(), float(params.number("cache_resolution"))),
        cache_params, [&](std::size_t i) { return lights[i].type != LightType::Environment; },
        [&](std::size_t i) {
          return i >= placements_.size() || !(placements[i] == placements_[i]) || sizes[i] != sizes_[i];
        },
        [&](std::size_t i, vec3 p) { return cone.transmittance(int(i), p, sample_light(lights[i], p)); }));
      placements_ = std::move(placements);
      sizes_ = std::move(sizes);
    }
    // The planes' caches follow the 3D caches (rebuilds_ counts every
    // change of what the cones read, the lights' sizes included) and the
    // planes; a plane move rebuilds only them, which rebuilds() does not
    // count (the device mirrors see it through plane_builds_).
    const Box3 box = cone.box;
    // One node per voxel: a floor's penumbra is sharper than the volume's
    // lit samples need (a grid of the 3D cache's cells widened the edge
    // penumbra of EdgePenumbraScalesWithTheLightsAngle by 15 %).
    plane_builds_ += std::uint64_t(plane_caches_.update(
        lights, scene.planes(), box, voxel, rebuilds_,
        [&](int i, vec3 p) { return cone.transmittance(i, p, sample_light(lights[std::size_t(i)], p)); }));
  }

  void render(const Scene& scene, Image& image, RenderStats* stats) override {
    RenderView view = resources_.view(scene);
    view.structures = rebuilds_ + plane_builds_;  // the tables' and caches' version, for device mirrors
    const Shading shading = scene.material().shading;
    if (caches_.built()) {
      const CachedConeMarch cached{cone_, caches_.views(), plane_caches_.view()};
      render_lit(view, cached, shading, image, stats);
    } else {
      render_lit(view, cone_, shading, image, stats);
    }
  }

  std::uint64_t aux_bytes() const override { return table_.bytes() + caches_.bytes() + plane_caches_.bytes(); }
  // The table build and each light's cache build count one each.
  std::uint64_t rebuilds() const override { return rebuilds_; }

 private:
  SceneResources resources_;
  VolumeAlignedTable table_{"cone-shadows summed-area table"};
  ConeMarch cone_;
  LightVisibilityCaches caches_;
  std::vector<LightPlacement> placements_;  // what the caches were built for
  std::vector<vec4> sizes_;                 // and the lights' sizes (with derived cones)
  PlaneCaches plane_caches_;
  std::uint64_t rebuilds_ = 0;
  std::uint64_t plane_builds_ = 0;
};

}  // namespace

TechniqueInfo cone_shadows_info() {
  return TechniqueInfo{
      "cone-shadows",
      "soft shadows from cones of growing cubes in a volume-aligned SAT (Schlegel et al. 2011)",
      ParameterTable{{
          ParameterSpec::real("cone_angle_deg", -1.0, -1.0, 45.0,
                              "half-angle of the shadow cone in degrees (< 0 = from each light's size; 5 for "
                              "directional and point lights)"),
          ParameterSpec::real("step_voxels", 4.0, 0.5, 64.0, "cone step length in voxels"),
          ParameterSpec::real("sat_resolution", 1.0, 0.1, 2.0, "summed-area table cells per voxel along each axis"),
          ParameterSpec::flag("shadow_cache", true, "store each light's transmittance on a grid instead of marching cones per sample"),
          ParameterSpec::real("cache_resolution", 0.5, 0.05, 2.0, "shadow cache grid size as a fraction of the data grid"),
          ParameterSpec::real("shadow_density_scale", 1.0, 0.0, 100.0, "multiplies the optical depth (0 = unshadowed)"),
      }},
      [] { return std::make_unique<ConeShadows>(); }};
}

}  // namespace penumbra

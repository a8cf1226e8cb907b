#include "penumbra/techniques/shadow_map/shadow_map.h"

#include "penumbra/techniques/light_space/light_map_technique.h"
#include "penumbra/techniques/shadow_map/shadow_map_kernels.h"

namespace penumbra {
namespace {

class ShadowMap final : public LightMapTechnique {
 public:
  void prepare(const Scene& scene, const ParameterValues& params) override {
    // pcf_radius unset (< 0): PCSS for the lights with a size, r = 0 for
    // the others (shadow_map.h).
    const int pcf_radius = params.integer("pcf_radius");
    pcf_radius_ = pcf_radius < 0 ? 0 : pcf_radius;
    pcss_ = make_pcss(scene.lights(), pcf_radius < 0 && pcss_enabled(params));
    slope_bias_ = float(params.number("slope_bias"));
    bias_ = float(params.number("depth_bias")) * scene.volume_view().min_spacing();
    const int resolution = params.integer("resolution");
    const float threshold = float(params.number("threshold"));
    update_maps(scene, resolution, {double(resolution), double(threshold)},
                [&](const RenderView& view, int, const LightProjection& projection) {
                  return build_shadow_map(view, projection, threshold);
                });
  }

  void render(const Scene& scene, Image& image, RenderStats* stats) override {
    render_lit(scene, ShadowMapVisibility{views(), pcf_radius_, bias_, slope_bias_, pcss_}, image, stats);
  }

 private:
  int pcf_radius_ = 0;
  float bias_ = 0.0f;
  float slope_bias_ = 1.0f;
  Pcss pcss_{};
};

}  // namespace

TechniqueInfo shadow_map_info() {
  return TechniqueInfo{
      "shadow-map",
      "shadow map with an opacity-threshold depth and a binary depth test (Weidner & Linsen's baseline)",
      ParameterTable{{
          light_map_resolution_parameter(),
          ParameterSpec::real("threshold", 0.5, 0.01, 0.999,
                              "accumulated opacity along the light ray that marks the occluder's depth"),
          ParameterSpec::integer("pcf_radius", -1, -1, 8,
                                 "percentage-closer filtering over (2r+1)^2 texels (0 = one binary test; < 0 = "
                                 "unset: PCSS sized by a light with a size, see soft, else 0)"),
          ParameterSpec::real("depth_bias", 1.0, 0.0, 16.0,
                              "added to the stored depth against self-shadowing, in voxels"),
          ParameterSpec::real("slope_bias", 1.0, 0.0, 4.0,
                              "adds this many times the occluder's depth change over the texels a tap stands "
                              "for (against acne on grazing surfaces; 0: constant bias only)"),
          pcss_parameter(),
      }},
      [] { return std::make_unique<ShadowMap>(); }};
}

}  // namespace penumbra

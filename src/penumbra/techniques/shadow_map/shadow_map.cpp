#include "penumbra/techniques/shadow_map/shadow_map.h"

#include "penumbra/render/lighting.h"
#include "penumbra/render/scene_resources.h"
#include "penumbra/techniques/light_space/light_map_set.h"
#include "penumbra/techniques/shadow_map/shadow_map_kernels.h"

namespace penumbra {
namespace {

class ShadowMap final : public Technique {
 public:
  void prepare(const Scene& scene, const ParameterValues& params) override {
    const bool shared_changed = resources_.update(scene);
    pcf_radius_ = params.integer("pcf_radius");
    bias_ = float(params.number("depth_bias")) * scene.volume_view().min_spacing();
    const int resolution = params.integer("resolution");
    const float threshold = float(params.number("threshold"));
    std::vector<double> key{double(resolution), double(threshold)};
    if (!maps_.stale(scene, shared_changed, key)) return;
    const RenderView view = resources_.shadow_view(scene);
    maps_.rebuild(scene, view, resolution, std::move(key), [&](int, const LightProjection& projection) {
      return build_shadow_map(view, projection, threshold);
    });
    ++rebuilds_;
  }

  void render(const Scene& scene, Image& image, RenderStats* stats) override {
    maps_.check_ready(scene);
    const RenderView view = resources_.view(scene);
    const ShadowMapVisibility visibility{maps_.views(), pcf_radius_, bias_};
    render_image(
        view,
        [&](const auto&) {
          return ScatteringLighting<ShadowMapVisibility>{&view, visibility, scene.material().shading};
        },
        image, stats);
  }

  std::uint64_t aux_bytes() const override { return maps_.bytes(); }
  std::uint64_t rebuilds() const override { return rebuilds_; }

 private:
  SceneResources resources_;
  LightMapSet maps_;
  int pcf_radius_ = 0;
  float bias_ = 0.0f;
  std::uint64_t rebuilds_ = 0;
};

}  // namespace

TechniqueInfo shadow_map_info() {
  return TechniqueInfo{
      "shadow-map",
      "shadow map with an opacity-threshold depth and a binary depth test (Weidner & Linsen's baseline)",
      ParameterTable{{
          ParameterSpec::integer("resolution", 1024, 256, 4096,
                                 "map texels per side (half per cube face for a point light in or near the volume)"),
          ParameterSpec::real("threshold", 0.5, 0.01, 0.999,
                              "accumulated opacity along the light ray that marks the occluder's depth"),
          ParameterSpec::integer("pcf_radius", 0, 0, 8,
                                 "percentage-closer filtering over (2r+1)^2 texels (0 = one binary test)"),
          ParameterSpec::real("depth_bias", 1.0, 0.0, 16.0,
                              "added to the stored depth against self-shadowing, in voxels"),
      }},
      [] { return std::make_unique<ShadowMap>(); }};
}

}  // namespace penumbra

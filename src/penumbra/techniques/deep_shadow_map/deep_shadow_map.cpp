#include "penumbra/techniques/deep_shadow_map/deep_shadow_map.h"

#include "penumbra/render/lighting.h"
#include "penumbra/render/scene_resources.h"
#include "penumbra/techniques/deep_shadow_map/deep_shadow_map_kernels.h"
#include "penumbra/techniques/light_space/light_map_set.h"

namespace penumbra {
namespace {

class DeepShadowMap final : public Technique {
 public:
  void prepare(const Scene& scene, const ParameterValues& params) override {
    const bool shared_changed = resources_.update(scene);
    bilinear_ = params.choice("filter") == "bilinear";
    const int resolution = params.integer("resolution");
    const int node_count = params.integer("nodes");
    const float tolerance = float(params.number("tolerance"));
    const bool colored = params.flag("colored");
    std::vector<double> key{double(resolution), double(node_count), double(tolerance), double(colored)};
    if (!maps_.stale(scene, shared_changed, key)) return;
    const RenderView view = resources_.shadow_view(scene);
    maps_.rebuild(scene, view, resolution, std::move(key), [&](int, const LightProjection& projection) {
      return build_deep_shadow_map(view, projection, node_count, tolerance, colored);
    });
    node_count_ = node_count;
    ++rebuilds_;
  }

  void render(const Scene& scene, Image& image, RenderStats* stats) override {
    maps_.check_ready(scene);
    const RenderView view = resources_.view(scene);
    const DeepShadowVisibility visibility{maps_.views(), node_count_, bilinear_};
    render_image(
        view,
        [&](const auto&) {
          return ScatteringLighting<DeepShadowVisibility>{&view, visibility, scene.material().shading};
        },
        image, stats);
  }

  std::uint64_t aux_bytes() const override { return maps_.bytes(); }
  std::uint64_t rebuilds() const override { return rebuilds_; }

 private:
  SceneResources resources_;
  LightMapSet maps_;
  int node_count_ = 0;
  bool bilinear_ = false;
  std::uint64_t rebuilds_ = 0;
};

}  // namespace

TechniqueInfo deep_shadow_map_info() {
  return TechniqueInfo{
      "deep-shadow-map",
      "deep shadow map: per-texel piecewise-linear coloured transmittance with N nodes (Lokovic & Veach; "
      "Weidner & Linsen's baseline)",
      ParameterTable{{
          ParameterSpec::integer("resolution", 1024, 256, 4096,
                                 "map texels per side (half per cube face for a point light in or near the volume)"),
          ParameterSpec::integer("nodes", 3, 2, kMaxDeepShadowNodes,
                                 "nodes (depth, r, g, b) per texel approximating the transmittance"),
          ParameterSpec::real("tolerance", 0.01, 0.001, 0.25,
                              "compression error bound, raised per texel (up to 32x) until the nodes suffice"),
          ParameterSpec::flag("colored", true,
                              "transmit the TF colour (1 - alpha (1 - t)); false: grey 1 - alpha as shadow-rays"),
          ParameterSpec::choice("filter", "nearest", {"nearest", "bilinear"},
                                "texel lookup: nearest, or bilinear over the four nearest texels"),
      }},
      [] { return std::make_unique<DeepShadowMap>(); }};
}

}  // namespace penumbra

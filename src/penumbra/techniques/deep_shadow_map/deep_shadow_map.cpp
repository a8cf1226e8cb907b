#include "penumbra/techniques/deep_shadow_map/deep_shadow_map.h"

#include "penumbra/techniques/deep_shadow_map/deep_shadow_map_kernels.h"
#include "penumbra/techniques/light_space/light_map_technique.h"

namespace penumbra {
namespace {

class DeepShadowMap final : public LightMapTechnique {
 public:
  void prepare(const Scene& scene, const ParameterValues& params) override {
    bilinear_ = params.choice("filter") == "bilinear";
    const int resolution = params.integer("resolution");
    const int node_count = params.integer("nodes");
    const float tolerance = float(params.number("tolerance"));
    const bool colored = params.flag("colored");
    update_maps(scene, resolution, {double(resolution), double(node_count), double(tolerance), double(colored)},
                [&](const RenderView& view, int, const LightProjection& projection) {
                  return build_deep_shadow_map(view, projection, node_count, tolerance, colored);
                });
    node_count_ = node_count;  // the maps' node count: `nodes` is part of their key
  }

  void render(const Scene& scene, Image& image, RenderStats* stats) override {
    render_lit(scene, DeepShadowVisibility{views(), node_count_, bilinear_}, image, stats);
  }

 private:
  int node_count_ = 0;
  bool bilinear_ = false;
};

}  // namespace

TechniqueInfo deep_shadow_map_info() {
  return TechniqueInfo{
      "deep-shadow-map",
      "deep shadow map: per-texel piecewise-linear coloured transmittance with N nodes (Lokovic & Veach; "
      "Weidner & Linsen's baseline)",
      ParameterTable{{
          light_map_resolution_parameter(),
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

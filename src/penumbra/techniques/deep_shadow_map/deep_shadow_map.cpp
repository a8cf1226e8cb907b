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
    slope_bias_ = float(params.number("slope_bias"));
    pcss_ = make_pcss(scene.lights(), pcss_enabled(params));
    const ShadowColorModel colors = shadow_color_model(params);
    std::vector<double> key = {double(resolution), double(node_count), double(tolerance)};
    for (double k : shadow_color_key(colors)) key.push_back(k);
    update_maps(scene, resolution, std::move(key), [&](const RenderView& view, int, const LightProjection& projection) {
      return build_deep_shadow_map(view, projection, node_count, tolerance, colors);
    });
    node_count_ = node_count;  // the maps' node count: `nodes` is part of their key
  }

  void render(const Scene& scene, Image& image, RenderStats* stats) override {
    render_lit(scene, DeepShadowVisibility{views(), node_count_, bilinear_, slope_bias_, pcss_}, image, stats);
  }

 private:
  int node_count_ = 0;
  bool bilinear_ = false;
  float slope_bias_ = 1.0f;
  Pcss pcss_{};
};

}  // namespace

TechniqueInfo deep_shadow_map_info() {
  return TechniqueInfo{
      "deep-shadow-map",
      "deep shadow map: per-texel piecewise-linear coloured transmittance with N nodes (Lokovic & Veach; "
      "Weidner & Linsen's baseline)",
      ParameterTable{with_shadow_color_parameters({
          light_map_resolution_parameter(),
          ParameterSpec::integer("nodes", 3, 2, kMaxDeepShadowNodes,
                                 "nodes (depth, r, g, b) per texel approximating the transmittance"),
          ParameterSpec::real("tolerance", 0.01, 0.001, 0.25,
                              "compression error bound, raised per texel (up to 32x) until the nodes suffice"),
          ParameterSpec::choice("filter", "nearest", {"nearest", "bilinear"},
                                "texel lookup: nearest, or bilinear over the four nearest texels"),
          ParameterSpec::real("slope_bias", 1.0, 0.0, 4.0,
                              "moves lookups toward the light by this many times the occluder's depth change "
                              "over the texels read (against moire on grazing surfaces; 0: none)"),
          pcss_parameter(),
      })},
      [] { return std::make_unique<DeepShadowMap>(); }};
}

}  // namespace penumbra

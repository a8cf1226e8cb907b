#include "penumbra/techniques/cssm/cssm.h"

#include "penumbra/techniques/cssm/cssm_kernels.h"
#include "penumbra/techniques/light_space/light_map_technique.h"

#include <string>

namespace penumbra {
namespace {

class Cssm final : public LightMapTechnique {
 public:
  void prepare(const Scene& scene, const ParameterValues& params) override {
    offset_count_ = std::stoi(params.choice("offsets"));
    // offset_scale unset (< 0): PCSS for the lights with a size, the
    // paper's offsets (scale 1) for the others (cssm.h).
    const double offset_scale = params.number("offset_scale");
    offset_scale_ = offset_scale < 0.0 ? 1.0f : float(offset_scale);
    pcss_ = make_pcss(scene.lights(), offset_scale < 0.0 && pcss_enabled(params));
    const int resolution = params.integer("resolution");
    const auto seed = std::uint32_t(params.integer("seed"));
    depth_aware_ = params.choice("filter") == "depth-aware";
    const ShadowColorModel colors = shadow_color_model(params);
    std::vector<double> key = {double(resolution), double(seed)};
    for (double k : shadow_color_key(colors)) key.push_back(k);
    update_maps(scene, resolution, std::move(key),
                [&](const RenderView& view, int light, const LightProjection& projection) {
                  return build_cssm(view, projection, seed, light, colors);
                });
  }

  void render(const Scene& scene, Image& image, RenderStats* stats) override {
    render_lit(scene, make_cssm_visibility(views(), offset_count_, offset_scale_, depth_aware_, pcss_), image, stats);
  }

 private:
  int offset_count_ = 13;
  float offset_scale_ = 1.0f;
  bool depth_aware_ = true;
  Pcss pcss_{};
};

}  // namespace

TechniqueInfo cssm_info() {
  return TechniqueInfo{
      "cssm",
      "colored stochastic shadow map: per-channel stochastic depths, averaged over m offsets (Weidner & Linsen)",
      ParameterTable{with_shadow_color_parameters({
          light_map_resolution_parameter(),
          ParameterSpec::choice("offsets", "13", {"7", "13", "21", "37"}, "depth tests averaged per lookup (Fig. 2)"),
          ParameterSpec::real("offset_scale", -1.0, -1.0, 8.0,
                              "multiplies the offsets (in texels of the map; < 0 = unset: PCSS sized by a light "
                              "with a size, see soft, else 1)"),
          ParameterSpec::choice("filter", "depth-aware", {"depth-aware", "paper"},
                                "depth-aware: taps read at the sample's depth below the occluder's entry plane, "
                                "taps off that plane dropped; paper: every tap at the sample's depth"),
          ParameterSpec::integer("seed", 0, 0, 1 << 30, "random seed of the map generation"),
          pcss_parameter(),
      })},
      [] { return std::make_unique<Cssm>(); }};
}

}  // namespace penumbra

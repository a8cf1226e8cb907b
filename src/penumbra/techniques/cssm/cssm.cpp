#include "penumbra/techniques/cssm/cssm.h"

#include "penumbra/render/lighting.h"
#include "penumbra/render/scene_resources.h"
#include "penumbra/techniques/cssm/cssm_kernels.h"
#include "penumbra/techniques/light_space/light_map_set.h"

#include <string>

namespace penumbra {
namespace {

class Cssm final : public Technique {
 public:
  void prepare(const Scene& scene, const ParameterValues& params) override {
    const bool shared_changed = resources_.update(scene);
    offset_count_ = std::stoi(params.choice("offsets"));
    offset_scale_ = float(params.number("offset_scale"));
    const int resolution = params.integer("resolution");
    const auto seed = std::uint32_t(params.integer("seed"));
    const bool colored = params.flag("colored");
    std::vector<double> key{double(resolution), double(seed), double(colored)};
    if (!maps_.stale(scene, shared_changed, key)) return;
    const RenderView view = resources_.shadow_view(scene);
    maps_.rebuild(scene, view, resolution, std::move(key), [&](int light, const LightProjection& projection) {
      return build_cssm(view, projection, seed, light, colored);
    });
    ++rebuilds_;
  }

  void render(const Scene& scene, Image& image, RenderStats* stats) override {
    maps_.check_ready(scene);
    const RenderView view = resources_.view(scene);
    const CssmVisibility visibility = make_cssm_visibility(maps_.views(), offset_count_, offset_scale_);
    render_image(
        view,
        [&](const auto&) { return ScatteringLighting<CssmVisibility>{&view, visibility, scene.material().shading}; },
        image, stats);
  }

  std::uint64_t aux_bytes() const override { return maps_.bytes(); }
  std::uint64_t rebuilds() const override { return rebuilds_; }

 private:
  SceneResources resources_;
  LightMapSet maps_;
  int offset_count_ = 13;
  float offset_scale_ = 1.0f;
  std::uint64_t rebuilds_ = 0;
};

}  // namespace

TechniqueInfo cssm_info() {
  return TechniqueInfo{
      "cssm",
      "colored stochastic shadow map: per-channel stochastic depths, averaged over m offsets (Weidner & Linsen)",
      ParameterTable{{
          ParameterSpec::integer("resolution", 1024, 256, 4096,
                                 "map texels per side (half per cube face for a point light in or near the volume)"),
          ParameterSpec::choice("offsets", "13", {"7", "13", "21"}, "depth tests averaged per lookup (Fig. 2)"),
          ParameterSpec::real("offset_scale", 1.0, 0.0, 8.0,
                              "multiplies the offsets (texels of a 1024^2 map, scaled with resolution)"),
          ParameterSpec::integer("seed", 0, 0, 1 << 30, "random seed of the map generation"),
          ParameterSpec::flag("colored", true,
                              "stop photons with alpha (1 - t), t the TF colour; false: alpha (grey shadows)"),
      }},
      [] { return std::make_unique<Cssm>(); }};
}

}  // namespace penumbra

#include "penumbra/techniques/emission_absorption/emission_absorption.h"

#include "penumbra/render/lighting.h"
#include "penumbra/render/scene_resources.h"

namespace penumbra {
namespace {

class EmissionAbsorption final : public Technique {
 public:
  void prepare(const Scene& scene, const ParameterValues&) override { resources_.update(scene); }

  void render(const Scene& scene, Image& image, RenderStats* stats) override {
    const RenderView view = resources_.view(scene);
    render_image(view, [&](const auto&) { return EmissionLighting{&view}; }, image, stats);
  }

  std::uint64_t aux_bytes() const override { return 0; }

 private:
  SceneResources resources_;
};

}  // namespace

TechniqueInfo emission_absorption_info() {
  return TechniqueInfo{"emission-absorption", "unshaded DVR: the TF colour is emitted, no lights", ParameterTable{},
                       [] { return std::make_unique<EmissionAbsorption>(); }};
}

}  // namespace penumbra

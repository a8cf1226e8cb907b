#include "penumbra/techniques/phong/phong.h"

#include "penumbra/render/render_lit.h"
#include "penumbra/render/scene_resources.h"

namespace penumbra {
namespace {

class Phong final : public Technique {
 public:
  void prepare(const Scene& scene, const ParameterValues&) override { resources_.update(scene, /*normals=*/true); }

  void render(const Scene& scene, Image& image, RenderStats* stats) override {
    const RenderView view = resources_.view(scene);
    render_lit(view, NoShadows{}, Shading::Phong, image, stats);
  }

  std::uint64_t aux_bytes() const override { return 0; }

 private:
  SceneResources resources_;
};

}  // namespace

TechniqueInfo phong_info() {
  return TechniqueInfo{"phong", "gradient Blinn-Phong shading, any number of lights, no shadows", ParameterTable{},
                       [] { return std::make_unique<Phong>(); }};
}

}  // namespace penumbra

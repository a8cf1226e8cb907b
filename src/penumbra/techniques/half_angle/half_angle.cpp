#include "penumbra/techniques/half_angle/half_angle.h"

#include "penumbra/techniques/half_angle/half_angle_renderer.h"

namespace penumbra {
namespace {

class HalfAngle final : public Technique {
 public:
  void prepare(const Scene& scene, const ParameterValues& params) override {
    HalfAngleSettings s;
    s.slices = params.integer("slices");
    s.cone_angle_deg = float(params.number("cone_angle_deg"));
    s.albedo = float(params.number("albedo"));
    s.light_buffer_size = params.integer("light_buffer_size");
    renderer_.prepare(scene, s);
  }

  void render(const Scene& scene, Image& image, RenderStats* stats) override { renderer_.render(scene, image, stats); }

  std::uint64_t aux_bytes() const override { return renderer_.aux_bytes(); }
  std::uint64_t rebuilds() const override { return renderer_.rebuilds(); }

 private:
  HalfAngleRenderer renderer_;
};

}  // namespace

TechniqueInfo half_angle_info() {
  return TechniqueInfo{
      "half-angle",
      "half-angle slicing with a light buffer, attenuated and blurred per slice (Kniss et al. 2002/2003)",
      ParameterTable{{
          ParameterSpec::integer("slices", 0, 0, 16384,
                                 "slices through the volume (0 = one per ray step along the view)"),
          ParameterSpec::real("cone_angle_deg", 20.0, 0.0, 80.0,
                              "half-angle of the forward-scattering cone toward the light"),
          ParameterSpec::real("albedo", 0.0, 0.0, 1.0,
                              "blend of forward multiple scattering (0 = single scattering, as shadow-rays)"),
          ParameterSpec::integer("light_buffer_size", 0, 0, 4096,
                                 "light buffer texels per side (0 = the image's larger side or one texel per pixel at the volume if finer)"),
      }},
      [] { return std::make_unique<HalfAngle>(); }};
}

}  // namespace penumbra

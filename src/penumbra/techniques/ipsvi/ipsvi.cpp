#include "penumbra/techniques/ipsvi/ipsvi.h"

#include "penumbra/techniques/ipsvi/sweep_renderer.h"

namespace penumbra {
namespace {

class Ipsvi final : public Technique {
 public:
  void prepare(const Scene& scene, const ParameterValues& params) override {
    IpsviSettings s;
    s.albedo = float(params.number("albedo"));
    s.cone_angle_deg = float(params.number("cone_angle_deg"));
    s.line_width = params.integer("line_width");
    s.cache_size = params.integer("cache_size");
    s.piecewise_integration = params.flag("piecewise_integration");
    s.early_termination = params.flag("early_termination");
    s.light_model = params.choice("light_model") == "paper" ? IpsviLightModel::Paper : IpsviLightModel::Grey;
    renderer_.prepare(scene, s);
  }

  void render(const Scene& scene, Image& image, RenderStats* stats) override { renderer_.render(scene, image, stats); }

  std::uint64_t aux_bytes() const override { return renderer_.aux_bytes(); }
  std::uint64_t rebuilds() const override { return renderer_.rebuilds(); }

 private:
  IpsviRenderer renderer_;
};

}  // namespace

TechniqueInfo ipsvi_info() {
  return TechniqueInfo{
      "ipsvi",
      "image plane sweep volume illumination: shadows and forward scattering via a 2D light-space cache (Sunden et al. 2011)",
      ParameterTable{{
          ParameterSpec::real("albedo", 0.0, 0.0, 1.0,
                              "blend of forward multiple scattering (0 = single scattering, as shadow-rays)"),
          ParameterSpec::real("cone_angle_deg", 20.0, 0.0, 80.0,
                              "half-angle of the forward-scattering cone toward the light"),
          ParameterSpec::integer("line_width", 1, 1, 64, "image lines per synchronised block"),
          ParameterSpec::integer("cache_size", 0, 0, 4096,
                                 "illumination cache texels per side over the visible part (0 = about one texel per pixel; else >= 16)"),
          ParameterSpec::flag("piecewise_integration", true,
                              "march light segments back to the previous cache plane (else one step per sample)"),
          ParameterSpec::flag("early_termination", false,
                              "ERT extension: a low-resolution pre-pass finds where each ray may stop"),
          ParameterSpec::choice("light_model", "grey", {"grey", "paper"},
                                "grey: a grey transmittance and one albedo (shadow-rays' model); paper: Eq. 3's light "
                                "coloured by the medium it crosses, a(s) = albedo x the sample's scattering albedo, "
                                "cone-mean phase for the scattered part"),
      }},
      [] { return std::make_unique<Ipsvi>(); }};
}

}  // namespace penumbra

#include "penumbra/techniques/convolution/convolution.h"

#include "penumbra/techniques/convolution/slab_renderer.h"

#include <string>

namespace penumbra {
namespace {

class Convolution final : public Technique {
 public:
  void prepare(const Scene& scene, const ParameterValues& params) override {
    SlabSettings s;
    s.slab_distance_voxels = float(params.number("slab_distance"));
    s.optimal_distance_voxels = float(params.number("optimal_distance"));
    s.kernel = parse_slab_kernel(params.choice("kernel"));
    s.kernel_samples = params.integer("kernel_samples");
    s.light.sigma_x2 = float(params.number("light_sigma_x2"));
    s.light.sigma_y2 = float(params.number("light_sigma_y2"));
    s.light.rotation_deg = float(params.number("light_rotation_deg"));
    s.seed = std::uint64_t(params.integer("seed"));
    s.preintegrated = params.flag("preintegrated");
    s.guard_band = params.flag("guard_band");
    s.carried_light = params.flag("carried_light");
    const std::string jitter = params.choice("jitter");
    s.jitter = jitter == "on" || (jitter == "scene" && scene.render().jitter);
    renderer_.prepare(scene, s);
  }

  void render(const Scene& scene, Image& image, RenderStats* stats) override { renderer_.render(scene, image, stats); }

  std::uint64_t aux_bytes() const override { return renderer_.aux_bytes(); }
  std::uint64_t rebuilds() const override { return std::uint64_t(renderer_.rebuilds()); }

 private:
  SlabRenderer renderer_;
};

}  // namespace

TechniqueInfo convolution_info() {
  return TechniqueInfo{
      "convolution",
      "iterative convolution shadows on view-aligned slabs from distant Gaussian lights (Patel et al. 2013)",
      ParameterTable{{
          ParameterSpec::real("slab_distance", 0.0, 0.0, 1000.0, "slab distance e in voxels (0 = the render step, or less where the meshes' detail or an oblique light needs it)"),
          ParameterSpec::real("optimal_distance", 0.0, 0.0, 100000.0,
                              "optimal shadow distance d1 in voxels (0 = a quarter of the box depth)"),
          ParameterSpec::choice("kernel", "ellipse", {"gaussian", "poisson", "ellipse"},
                                "slab convolution kernel"),
          ParameterSpec::integer("kernel_samples", 0, 0, 64,
                                 "taps: ellipse N (default 2), poisson N (8), gaussian M x M (19, odd); 0 = default, at least 2"),
          ParameterSpec::real("light_sigma_x2", -1.0, -1.0, 100.0,
                              "light variance along its x axis on the virtual light plane (< 0 = from the scene light)"),
          ParameterSpec::real("light_sigma_y2", 0.0, 0.0, 100.0,
                              "light variance along its y axis (used with light_sigma_x2 >= 0)"),
          ParameterSpec::real("light_rotation_deg", 0.0, -180.0, 180.0,
                              "rotation alpha of the light's x axis from camera right (with light_sigma_x2 >= 0)"),
          ParameterSpec::integer("seed", 1, 0, 1 << 30, "seed of the random kernel rotations"),
          ParameterSpec::flag("preintegrated", false,
                              "preintegrated compositing of the volume between slabs (Engel et al. 2001)"),
          ParameterSpec::flag("guard_band", true,
                              "sweep the light buffers over a band around the image, so occluders just outside it shadow"),
          ParameterSpec::flag("carried_light", true,
                              "zero-variance lights on buffers that follow their rays (no re-sampling blur; off: re-sampled every slab)"),
          ParameterSpec::choice("jitter", "scene", {"scene", "on", "off"},
                                "per-pixel sample offset within each slab (scene: the scene's render.jitter)"),
      }},
      [] { return std::make_unique<Convolution>(); },
      /*draws_meshes=*/true};
}

}  // namespace penumbra

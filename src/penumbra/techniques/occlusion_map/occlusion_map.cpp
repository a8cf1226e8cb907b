#include "penumbra/techniques/occlusion_map/occlusion_map.h"

#include "penumbra/render/scene_resources.h"
#include "penumbra/techniques/occlusion_map/iso_occupancy.h"
#include "penumbra/techniques/occlusion_map/isosurface_render.h"
#include "penumbra/techniques/occlusion_map/moment_pyramid.h"

#include <optional>

namespace penumbra {
namespace {

// The angular radius of directional and point lights when light_size_deg is
// unset (its default before issue 18).
constexpr float kDefaultLightSizeDeg = 3.0f;

ShadowMode shadow_mode(const std::string& name) {
  if (name == "hard") return ShadowMode::Hard;
  if (name == "soft") return ShadowMode::Soft;
  return ShadowMode::None;
}

class OcclusionMap final : public Technique {
 public:
  void prepare(const Scene& scene, const ParameterValues& params) override {
    dvr_ = params.choice("mode") == "dvr";
    resources_.update(scene, dvr_ && scene.material().shading == Shading::Phong);
    MomentPyramidSettings settings;
    settings.moments = params.integer("moments");
    settings.resolution = float(params.number("resolution"));
    settings.kernel_size = params.integer("kernel_size");
    settings.validate();

    const std::uint64_t data_version = scene.versions().data;
    const bool data_changed = data_version != data_version_;
    if (data_changed || pyramid_.empty() || !(settings == pyramid_.settings()) ||
        scene.clip_planes() != pyramid_.clip_planes()) {
      const ValueRange range = scene.volume().value_range();
      pyramid_ = MomentPyramid(scene.volume_view(), vec2(range.min, range.max), settings, scene.clip_planes());
      data_version_ = data_version;
      ++rebuilds_;
    }
    const vec2 tf_range = scene.tf_value_range();
    iso_ = tf_range.x + float(params.number("iso_value")) * (tf_range.y - tf_range.x);
    if (data_changed || !occupancy_ || occupancy_->iso_value() != iso_) {
      occupancy_.emplace(resources_.macrocells(), iso_);
    }
    shadows_ = dvr_ ? ShadowMode::None : shadow_mode(params.choice("shadows"));
    ambient_occlusion_ = params.flag("ambient_occlusion");
    const std::string& combine = params.choice("ao_combine");
    ao_combine_ = combine == "mean" ? AoCombine::Mean : (combine == "product" ? AoCombine::Product : AoCombine::Max);
    ao_offset_ = float(params.number("ao_offset"));
    ao_on_lights_ = params.flag("ao_lights");
    const float size = float(params.number("light_size_deg"));
    default_spread_ = std::tan(glm::radians(size < 0.0f ? kDefaultLightSizeDeg : size));
    forced_spread_ = size < 0.0f ? -1.0f : default_spread_;
  }

  void render(const Scene& scene, Image& image, RenderStats* stats) override {
    if (pyramid_.moments() == 4) {
      render_with<4>(scene, image, stats);
    } else {
      render_with<2>(scene, image, stats);
    }
  }

  std::uint64_t aux_bytes() const override { return pyramid_.bytes() + (occupancy_ ? occupancy_->bytes() : 0); }
  // Builds of the moment pyramid (the iso flag grid is not counted: it is
  // rebuilt with the iso-value by design and costs microseconds).
  std::uint64_t rebuilds() const override { return rebuilds_; }

 private:
  template <int K> void render_with(const Scene& scene, Image& image, RenderStats* stats) const {
    RenderView lit = resources_.view(scene);
    const float ambient = lit.material.ambient;
    lit.material.ambient = 0.0f;
    const RenderView iso_view = occupancy_->apply(lit);
    OcclusionShadingSetup<K> setup;
    setup.lit_view = &lit;
    setup.iso_view = &iso_view;
    setup.queries.pyramid = pyramid_.view<K>();
    setup.queries.box = lit.box;
    setup.queries.ao_offset = ao_offset_;
    setup.queries.ao_combine = ao_combine_;
    setup.queries.default_spread = default_spread_;
    setup.queries.forced_spread = forced_spread_;
    const vec2 range = pyramid_.value_range();
    setup.normalise = ValueNormalisation{range.x, range.y > range.x ? 1.0f / (range.y - range.x) : 1.0f};
    setup.iso = iso_;
    setup.iso_color = vec3(lit.tf.lookup(iso_));
    setup.ambient = ambient;
    setup.shadows = shadows_;
    setup.ambient_occlusion = ambient_occlusion_;
    setup.ao_on_lights = ao_on_lights_;
    if (!dvr_) {
      render_isosurface_image(setup, image, stats);
      return;
    }
    if (active_device() == Device::Cuda) note_cpu_fallback("occlusion-map in mode dvr");
    const Shading shading = scene.material().shading;
    render_image(
        lit,
        [&](const auto& sampler) {
          return DvrOcclusionLighting<K, std::decay_t<decltype(sampler)>>{&setup, sampler, shading};
        },
        image, stats);
  }

  SceneResources resources_;
  MomentPyramid pyramid_;
  std::optional<IsoOccupancy> occupancy_;
  std::uint64_t data_version_ = 0;
  std::uint64_t rebuilds_ = 0;
  bool dvr_ = false;
  float iso_ = 0.0f;
  ShadowMode shadows_ = ShadowMode::Soft;
  bool ambient_occlusion_ = true;
  AoCombine ao_combine_ = AoCombine::Product;
  float ao_offset_ = 2.0f;
  bool ao_on_lights_ = true;
  float default_spread_ = 0.0f;
  float forced_spread_ = -1.0f;
};

}  // namespace

TechniqueInfo occlusion_map_info() {
  return TechniqueInfo{
      "occlusion-map",
      "isosurface ray casting with ambient occlusion and soft shadows from a moment pyramid (Penner & Mitchell 2008)",
      ParameterTable{{
          ParameterSpec::real("iso_value", 0.5, 0.0, 1.0,
                              "iso-value normalised to the TF range (0 = range min, 1 = range max)"),
          ParameterSpec::choice("mode", "iso", {"iso", "dvr"},
                                "iso: isosurface ray casting; dvr: DVR with the same ambient occlusion (Fig. 11)"),
          ParameterSpec::choice("shadows", "soft", {"none", "hard", "soft"},
                                "isosurface shadows: none, hard (iso-test ray) or soft (occlusion-map march)"),
          ParameterSpec::flag("ambient_occlusion", true, "ambient occlusion from four pyramid levels along the normal"),
          ParameterSpec::choice("ao_combine", "product", {"max", "mean", "product"},
                                "combine the four levels' occlusion: max (the paper), mean, or product of the "
                                "unoccluded fractions"),
          ParameterSpec::real("ao_offset", 2.0, 0.0, 8.0,
                              "AO sample distance from the surface, in Gaussian sigmas of each level"),
          ParameterSpec::flag("ao_lights", true, "AO also darkens the lights, not only the ambient term"),
          ParameterSpec::real("light_size_deg", -1.0, -1.0, 45.0,
                              "angular radius of every light for soft shadows (< 0 = each light's own size; "
                              "3 for directional and point lights)"),
          ParameterSpec::integer("moments", 2, 2, 4, "2 (Chebyshev bound, the paper) or 4 (Hamburger bound)"),
          ParameterSpec::real("resolution", 0.5, 0.125, 1.0, "occlusion map level 0 as a fraction of the data grid"),
          ParameterSpec::integer("kernel_size", 5, 3, 15, "taps of level 0's Gaussian at level-0 resolution (odd)"),
      }},
      [] { return std::make_unique<OcclusionMap>(); }};
}

}  // namespace penumbra

#pragma once
// What shadow-map, deep-shadow-map and cssm share: a technique whose light
// visibility comes from one light-space map per light (LightMapSet). The
// derived class reads its parameters, calls update_maps() with the values
// that shape its maps and a builder, and renders through render_lit() with
// its Visibility functor over views().
#include "penumbra/render/render_lit.h"
#include "penumbra/render/scene_resources.h"
#include "penumbra/render/technique.h"
#include "penumbra/techniques/light_space/light_map_set.h"
#include "penumbra/techniques/light_space/light_ray.h"
#include "penumbra/techniques/light_space/pcss.h"

#include <cstdint>
#include <utility>
#include <vector>

namespace penumbra {

class LightMapTechnique : public Technique {
 public:
  std::uint64_t aux_bytes() const override { return maps_.bytes(); }
  std::uint64_t rebuilds() const override { return rebuilds_; }

 protected:
  // Rebuilds every light's map, build(shadow_view, light_index, projection),
  // when the data, the (shadow) TF, the lights, the clip planes, the step or
  // `key` (the map parameters) changed since the last build.
  template <class Build>
  void update_maps(const Scene& scene, int resolution, std::vector<double> key, const Build& build) {
    const bool shared_changed = resources_.update(scene);
    if (!maps_.stale(scene, shared_changed, key)) return;
    const RenderView view = resources_.shadow_view(scene);
    maps_.rebuild(scene, view, resolution, std::move(key),
                  [&](int light, const LightProjection& projection) { return build(view, light, projection); });
    ++rebuilds_;
  }

  // The map views, index i for the scene's light i.
  const LightMapView* views() const { return maps_.views(); }

  // One ray-casting pass lit through `visibility`.
  template <class Visibility>
  void render_lit(const Scene& scene, const Visibility& visibility, Image& image, RenderStats* stats) {
    maps_.check_ready(scene);
    RenderView view = resources_.view(scene);
    view.structures = rebuilds_;  // the maps' version, for device mirrors
    penumbra::render_lit(view, visibility, scene.material().shading, image, stats);
  }

 private:
  SceneResources resources_;
  LightMapSet maps_;
  std::uint64_t rebuilds_ = 0;
};

// The `resolution` parameter every light-map technique declares.
inline ParameterSpec light_map_resolution_parameter() {
  return ParameterSpec::integer("resolution", 1024, 256, 4096,
                                "map texels per side (half per cube face for a point light in or near the volume)");
}

// The `soft` parameter every light-map technique declares (issue 18,
// light_space/pcss.h): auto, the PCSS filter sized by each light that has a
// size (unless the technique's own softness knob is set), the paper's filter
// for the others; off (the default): the paper's filter for every light.
// An option, not the default, because it is worse on thick curved occluders:
// on head-distant-8 mean dE 1.38 -> 3.18 (deep-shadow-map), the skull's far
// side lit by filter taps whose parallel rays miss the skull, while on
// engine-distant-8 it is 2.53 -> 1.67 (docs/comparison-report.md).
inline ParameterSpec pcss_parameter() {
  return ParameterSpec::choice("soft", "off", {"auto", "off"},
                               "auto: a percentage-closer soft-shadow filter sized by each light's angle or radius "
                               "(lights without a size, or the softness knob set: the paper's filter); off: the "
                               "paper's filter");
}

inline bool pcss_enabled(const ParameterValues& params) { return params.choice("soft") == "auto"; }

// The colour parameters of the coloured maps (deep-shadow-map, cssm), see
// light_ray.h: `colored` (false: grey), `color_model` (chromatic, the
// default, or the paper's alpha (1 - t)) and `saturation` (chromatic).
inline std::vector<ParameterSpec> shadow_color_parameters() {
  return {
      ParameterSpec::flag("colored", true, "shadows take the hue of what they pass through (false: grey, as shadow-rays)"),
      ParameterSpec::choice("color_model", "chromatic", {"chromatic", "paper"},
                            "chromatic: the TF hue redistributes the extinction over r, g, b (an opaque white object "
                            "shadows as under shadow-rays); paper: Weidner & Linsen's 1 - alpha (1 - t), bright "
                            "material transmits"),
      ParameterSpec::real("saturation", 1.0, 0.0, double(kMaxShadowSaturation),
                          "chromatic model: how strongly the TF hue tints the shadow (0: grey)"),
  };
}

// `specs` followed by shadow_color_parameters().
inline std::vector<ParameterSpec> with_shadow_color_parameters(std::vector<ParameterSpec> specs) {
  for (ParameterSpec& s : shadow_color_parameters()) specs.push_back(std::move(s));
  return specs;
}

inline ShadowColorModel shadow_color_model(const ParameterValues& params) {
  ShadowColorModel m;
  if (!params.flag("colored")) {
    m.kind = ShadowColor::Grey;
  } else if (params.choice("color_model") == "paper") {
    m.kind = ShadowColor::Paper;
  } else {
    m.kind = ShadowColor::Chromatic;
    m.saturation = float(params.number("saturation"));
  }
  return m;
}

// The values of a colour model that shape a map (its rebuild key).
inline std::vector<double> shadow_color_key(const ShadowColorModel& m) {
  return {double(int(m.kind)), m.kind == ShadowColor::Chromatic ? double(m.saturation) : 0.0};
}

}  // namespace penumbra

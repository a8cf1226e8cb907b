#pragma once
// The maps of one light-space technique, one per scene light (index i of the
// scene's lights uses map i), and the bookkeeping that says when they must
// be rebuilt: the volume data, the (shadow) TF, the lights, the clip planes
// (scene geometry), the ray step, or the parameters that shape the maps.
// A camera move, a material change or a query-only parameter rebuilds
// nothing.
#include "penumbra/render/render_view.h"
#include "penumbra/scene/scene.h"
#include "penumbra/techniques/light_space/light_map.h"

#include <cstdint>
#include <string>
#include <vector>

namespace penumbra {

class LightMapSet {
 public:
  // `shared_changed`: what SceneResources::update returned (data or TF
  // changed). `key`: the values of the parameters the maps depend on.
  bool stale(const Scene& scene, bool shared_changed, const std::vector<double>& key) const;

  // Builds one map per light: make(light_index, projection) returns the
  // filled LightMap. Records what the maps were built from.
  // If `make` throws (OutOfMemoryBudget), the set is left empty and stale.
  template <class Make>
  void rebuild(const Scene& scene, const RenderView& view, int resolution, std::vector<double> key, Make&& make) {
    built_ = false;
    maps_.clear();  // before building: the old maps' memory is free for the new ones
    views_.clear();
    const std::vector<Light>& lights = scene.lights();
    for (std::size_t i = 0; i < lights.size(); ++i) {
      maps_.push_back(make(int(i), make_light_projection(lights[i], view.box, resolution)));
    }
    for (const LightMap& m : maps_) views_.push_back(m.view());
    record(scene, std::move(key));
  }

  // Throws InvalidArgument("technique") unless the maps were built for the
  // scene's lights (render() after a failed or missing prepare()).
  void check_ready(const Scene& scene) const;

  const LightMapView* views() const { return views_.data(); }
  const std::vector<LightMap>& maps() const { return maps_; }
  std::uint64_t bytes() const;

 private:
  void record(const Scene& scene, std::vector<double> key);

  bool built_ = false;
  std::uint64_t lights_version_ = 0;
  std::uint64_t geometry_version_ = 0;
  float step_ = 0.0f;
  std::vector<double> key_;
  std::vector<LightMap> maps_;
  std::vector<LightMapView> views_;
};

}  // namespace penumbra

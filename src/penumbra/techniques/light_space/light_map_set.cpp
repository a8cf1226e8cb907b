#include "penumbra/techniques/light_space/light_map_set.h"

#include "penumbra/base/error.h"

namespace penumbra {

bool LightMapSet::stale(const Scene& scene, bool shared_changed, const std::vector<double>& key) const {
  const SceneVersions& v = scene.versions();
  return !built_ || shared_changed || v.lights != lights_version_ || v.geometry != geometry_version_ ||
         scene.step_world() != step_ || key != key_;
}

void LightMapSet::record(const Scene& scene, std::vector<double> key) {
  built_ = true;
  lights_version_ = scene.versions().lights;
  geometry_version_ = scene.versions().geometry;
  step_ = scene.step_world();
  key_ = std::move(key);
}

void LightMapSet::check_ready(const Scene& scene) const {
  if (!built_ || maps_.size() != scene.lights().size()) {
    throw InvalidArgument("technique", "render() needs a successful prepare() with the scene's lights first");
  }
}

std::uint64_t LightMapSet::bytes() const {
  std::uint64_t total = 0;
  for (const LightMap& m : maps_) total += m.bytes();
  return total;
}

}  // namespace penumbra

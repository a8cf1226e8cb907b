#include "penumbra/io/scene_state.h"

namespace penumbra {

using nlohmann::json;

std::string volume_key_of(const json& scene_json) {
  const auto volume = scene_json.find("volume");
  if (volume == scene_json.end() || !volume->is_object()) return {};
  json section = *volume;
  section.erase("time_step");
  return section.dump();
}

bool SceneState::apply(const SceneUpdate& next) {
  const bool new_volume = next.volume_key != volume_key_;
  auto changed = [&](const char* key) {
    return new_volume || json_.value(key, json()).dump() != next.json.value(key, json()).dump();
  };
  const Scene& s = next.scene;
  bool data_changed = false;
  if (new_volume) {
    scene_.set_volume(s.volume_ptr(), s.time_step());
    scene_.set_volume_source(s.volume_source());
    data_changed = true;
  } else if (scene_.time_step() != s.time_step()) {
    scene_.set_time_step(s.time_step());
    data_changed = true;
  }
  if (changed("transfer_function")) scene_.set_transfer_function(s.transfer_function());
  if (changed("shadow_transfer_function")) scene_.set_shadow_transfer_function(s.shadow_transfer_function());
  if (changed("camera")) scene_.set_camera(s.camera());
  if (changed("lights")) scene_.set_lights(s.lights());
  if (changed("material")) scene_.set_material(s.material());
  if (changed("background")) scene_.set_background(s.background());
  if (changed("planes")) scene_.set_planes(s.planes());
  if (changed("clip_planes")) scene_.set_clip_planes(s.clip_planes());
  if (changed("render")) scene_.set_render(s.render());
  if (changed("meshes")) scene_.set_meshes(s.meshes());
  json_ = next.json;
  volume_key_ = next.volume_key;
  return data_changed;
}

}  // namespace penumbra

#include "scene_handle.h"

#include "penumbra/base/error.h"
#include "penumbra/io/scene_json.h"

#include <fmt/format.h>

namespace penumbra::python {

using nlohmann::json;

namespace {

// What parse_scene reads in place of an in-memory volume's section; the
// volume loader hands it the volume instead of opening a file.
constexpr const char* kMemoryVolumeFile = "<in-memory volume>";

// Sections whose keys an update merges into the scene's (a camera eye alone
// keeps the target); the others are replaced whole, as a scene file gives them.
bool merges_keys(const std::string& section) {
  return section == "camera" || section == "material" || section == "render";
}

}  // namespace

std::vector<std::string> changed_versions(const SceneVersions& a, const SceneVersions& b) {
  std::vector<std::string> out;
  const std::pair<const char*, bool> fields[] = {
      {"data", a.data != b.data},         {"transfer_function", a.transfer_function != b.transfer_function},
      {"lights", a.lights != b.lights},   {"camera", a.camera != b.camera},
      {"material", a.material != b.material}, {"geometry", a.geometry != b.geometry},
      {"render", a.render != b.render},   {"meshes", a.meshes != b.meshes}};
  for (const auto& [name, changed] : fields) {
    if (changed) out.emplace_back(name);
  }
  return out;
}

SceneHandle::SceneHandle(const json& scene_json, std::filesystem::path base_dir, std::shared_ptr<const Volume> volume)
    : base_dir_(std::move(base_dir)) {
  if (!scene_json.is_object()) throw InvalidScene("(root)", "expected a scene object");
  apply(scene_json, std::move(volume));
}

void SceneHandle::apply(json next, std::shared_ptr<const Volume> volume) {
  std::string key;
  if (volume) {
    json section = next.value("volume", json::object());
    if (!section.is_object()) throw InvalidScene("volume", "expected an object");
    for (const auto& item : section.items()) {
      if (item.key() != "time_step") {
        throw InvalidScene("volume." + item.key(), "an in-memory volume takes only time_step (set spacing and "
                                                   "origin on the Volume)");
      }
    }
    section["file"] = kMemoryVolumeFile;
    next["volume"] = section;
    key = fmt::format("memory:{}", static_cast<const void*>(volume.get()));
  } else {
    key = volume_key_of(next);
  }
  SceneParseOptions options;
  options.load_volume = [&](const VolumeSource& source, const std::filesystem::path& resolved) {
    if (volume) return volume;
    // The same volume section as before: the voxels loaded then, not a reread.
    if (!state_.empty() && key == state_.volume_key()) return state_.scene().volume_ptr();
    return load_scene_volume(source, resolved);
  };
  Scene scene = parse_scene(next.dump(), base_dir_, options);
  if (volume) scene.set_volume_source(VolumeSource{});
  // Sections are compared in their written form, so that a section given
  // with its defaults left out equals the same section written in full.
  json written = json::parse(write_scene_json(scene));
  if (volume) written["volume"] = {{"memory", key}, {"time_step", scene.time_step()}};
  state_.apply(SceneUpdate{std::move(scene), std::move(written), key});
  memory_volume_ = std::move(volume);
}

std::vector<std::string> SceneHandle::update(const json& sections, std::shared_ptr<const Volume> volume) {
  if (!sections.is_object()) throw InvalidScene("(root)", "expected an object of scene sections");
  const SceneVersions before = scene().versions();
  json next = to_json();
  bool names_volume_source = false;
  for (const auto& item : sections.items()) {
    const std::string& name = item.key();
    const json& value = item.value();
    if (name == "volume" && value.is_object()) names_volume_source = value.contains("file") || value.contains("builtin");
    if (value.is_null()) {
      next.erase(name);  // back to the default
    } else if ((name == "volume" ? !names_volume_source : merges_keys(name)) && value.is_object() &&
               next.contains(name) && next[name].is_object()) {
      for (const auto& field : value.items()) {
        if (field.value().is_null()) next[name].erase(field.key());
        else next[name][field.key()] = field.value();
      }
    } else {
      next[name] = value;
    }
  }
  if (volume) {
    // A new in-memory volume: of the volume section only time_step stays.
    json section = json::object();
    if (const auto given = sections.find("volume"); given != sections.end() && given->is_object()) {
      section = *given;
    }
    next["volume"] = section;
  } else if (memory_volume_ && !names_volume_source) {
    volume = memory_volume_;
  }
  apply(std::move(next), std::move(volume));
  return changed_versions(before, scene().versions());
}

std::vector<std::string> SceneHandle::orbit(float azimuth_deg, float elevation_deg) {
  Scene turned = scene();
  Camera camera = turned.camera();
  camera.orbit(azimuth_deg, elevation_deg);
  turned.set_camera(camera);
  return update(json{{"camera", json::parse(write_scene_json(turned))["camera"]}}, nullptr);
}

json SceneHandle::to_json() const {
  json j = json::parse(write_scene_json(scene()));
  if (memory_volume_) j["volume"] = {{"time_step", scene().time_step()}};
  return j;
}

}  // namespace penumbra::python

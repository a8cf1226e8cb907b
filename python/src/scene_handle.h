#pragma once
// The scene behind penumbra.Scene and penumbra.Renderer: a SceneState (the
// server's incremental updates, io/scene_state.h) fed with complete scenes in
// scene JSON v1, and the in-memory volume, if the scene's volume came from
// Python rather than from a file or a generator.
#include "penumbra/io/scene_state.h"

#include <filesystem>
#include <memory>

namespace penumbra::python {

class SceneHandle {
 public:
  // `json` is a complete scene (an object). With `volume` set, the scene
  // shows it (json's volume section holds at most time_step); else json names
  // a file (relative to base_dir) or a builtin. Throws as parse_scene does.
  SceneHandle(const nlohmann::json& json, std::filesystem::path base_dir, std::shared_ptr<const Volume> volume);

  // Replaces the top-level sections given (scene JSON v1 keys) and changes
  // only the parts of the scene whose sections differ. The keys of camera,
  // material and render merge into the scene's, and so do those of a volume
  // section that names no file or builtin (time_step alone); the other
  // sections replace the scene's whole. A `volume` replaces the in-memory
  // volume (then sections' volume holds at most time_step). Returns the
  // SceneVersions fields that moved, by name.
  std::vector<std::string> update(const nlohmann::json& sections, std::shared_ptr<const Volume> volume);

  // Turns the camera about its target (Camera::orbit) as an update would.
  std::vector<std::string> orbit(float azimuth_deg, float elevation_deg);

  const Scene& scene() const { return state_.scene(); }
  Scene& scene() { return state_.scene(); }
  const std::filesystem::path& base_dir() const { return base_dir_; }
  // The in-memory volume, or null when the scene names a file or a builtin.
  const std::shared_ptr<const Volume>& memory_volume() const { return memory_volume_; }
  // Scene JSON v1 of the scene as it is (every key written); for an
  // in-memory volume the volume section holds only time_step.
  nlohmann::json to_json() const;

 private:
  void apply(nlohmann::json json, std::shared_ptr<const Volume> volume);

  SceneState state_;
  std::filesystem::path base_dir_;
  std::shared_ptr<const Volume> memory_volume_;
};

// The SceneVersions fields that differ between two snapshots, by name.
std::vector<std::string> changed_versions(const SceneVersions& before, const SceneVersions& after);

}  // namespace penumbra::python

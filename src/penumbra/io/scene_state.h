#pragma once
// A scene that follows a stream of complete scenes (scene JSON v1), as a
// viewer or a script sends them. apply() changes only the parts of the scene
// that differ from the last scene applied, so the version counters move only
// for those: a camera move rebuilds no light-space structure. The HTTP server
// keeps one per session; the Python Renderer keeps one too.
#include "penumbra/scene/scene.h"

#include <nlohmann/json.hpp>

#include <string>

namespace penumbra {

// One complete scene and what it was parsed from.
struct SceneUpdate {
  Scene scene;
  nlohmann::json json;     // the scene's JSON (an object); its sections are compared
  std::string volume_key;  // identifies the volume; equal keys mean the same voxels
};

// The key of a scene's volume section: the section without time_step, so
// frames of one series share one key (and one loaded volume).
std::string volume_key_of(const nlohmann::json& scene_json);

class SceneState {
 public:
  bool empty() const { return volume_key_.empty(); }
  const Scene& scene() const { return scene_; }
  Scene& scene() { return scene_; }
  const nlohmann::json& json() const { return json_; }
  const std::string& volume_key() const { return volume_key_; }

  // Applies the parts of `next` whose JSON sections changed; returns whether
  // the volume or its time step changed.
  bool apply(const SceneUpdate& next);

 private:
  Scene scene_;
  nlohmann::json json_;
  std::string volume_key_;
};

}  // namespace penumbra

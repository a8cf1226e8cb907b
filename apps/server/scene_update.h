#pragma once
// Scenes sent by clients. parse_client_scene() reads scene JSON v1 as
// parse_scene() does, with what a server needs on top:
// - the volume file must lie in the data folder (DataDirectory), and the
//   volume comes from the shared VolumeCache instead of being read again;
// - preset files named in a scene are refused (a client could name any file
//   with them); the viewer imports presets through POST /api/presets;
// - builtin volumes are capped in size, and the technique and its parameters
//   are checked strictly (errors name "render.params.<name>").
// SceneState::apply() then changes only the parts of the session's scene that
// differ from the last scene applied, so the version counters move only for
// those: a camera move rebuilds no light-space structure.
#include "penumbra/scene/scene.h"
#include "server/data_directory.h"
#include "server/volume_cache.h"

#include <nlohmann/json.hpp>

#include <string>

namespace penumbra::server {

struct SceneLimits {
  int max_builtin_size = 256;  // voxels per axis of a procedural volume
};

struct ClientScene {
  Scene scene;
  nlohmann::json json;      // the client's scene (an object), for diffing
  std::string volume_key;   // identifies the volume (its section without time_step)
};

// Throws InvalidScene / HttpError naming the offending key, IoError for an
// unreadable volume file.
ClientScene parse_client_scene(const nlohmann::json& scene_json, const DataDirectory& data, VolumeCache& cache,
                               const SceneLimits& limits);

// The scene a session shows and the client JSON it was last made from.
class SceneState {
 public:
  bool empty() const { return volume_key_.empty(); }
  const Scene& scene() const { return scene_; }
  Scene& scene() { return scene_; }
  const nlohmann::json& json() const { return json_; }

  // Applies the parts of `next` that changed; returns whether the volume or
  // its time step changed.
  bool apply(const ClientScene& next);

 private:
  Scene scene_;
  nlohmann::json json_;
  std::string volume_key_;
};

}  // namespace penumbra::server

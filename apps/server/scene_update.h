#pragma once
// Scenes sent by clients. parse_client_scene() reads scene JSON v1 as
// parse_scene() does, with what a server needs on top:
// - the volume file must lie in the data folder (DataDirectory), and the
//   volume comes from the shared VolumeCache instead of being read again;
// - preset files named in a scene are refused (a client could name any file
//   with them); the viewer imports presets through POST /api/presets;
// - builtin volumes are capped in size, and the technique and its parameters
//   are checked strictly (errors name "render.params.<name>").
// SceneState::apply() (io/scene_state.h) then changes only the parts of the
// session's scene that differ from the last scene applied, so the version
// counters move only for those: a camera move rebuilds no light-space structure.
#include "penumbra/io/scene_state.h"
#include "penumbra/scene/scene.h"
#include "server/data_directory.h"
#include "server/volume_cache.h"

#include <nlohmann/json.hpp>

#include <string>

namespace penumbra::server {

struct SceneLimits {
  int max_builtin_size = 256;  // voxels per axis of a procedural volume
};

// The client's scene (json, an object, for diffing) and its volume's key.
using ClientScene = SceneUpdate;

// Throws InvalidScene / HttpError naming the offending key, IoError for an
// unreadable volume file.
ClientScene parse_client_scene(const nlohmann::json& scene_json, const DataDirectory& data, VolumeCache& cache,
                               const SceneLimits& limits);

}  // namespace penumbra::server

#pragma once
// Scene JSON, version 1 (DESIGN.md 4). Strict: an unknown key, a value of the
// wrong type or out of range is an InvalidScene naming the key path (for
// example "lights[1].direction"); missing keys take the documented defaults
// (docs/scene-format.md). Relative file paths are relative to the scene file.
#include "penumbra/scene/scene.h"

#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <string_view>

namespace penumbra {

// Reads and parses a scene file, loading its volume. IoError for an unreadable
// file, InvalidScene for bad content.
Scene load_scene(const std::filesystem::path& path);

struct SceneParseOptions {
  // Loads the volume a scene names: `source` as written (file or builtin,
  // spacing/origin overrides to apply) and, for files, the path resolved
  // against the scene's folder. Empty: load_scene_volume. A server passes
  // its own to check paths and share loaded volumes between sessions.
  std::function<std::shared_ptr<const Volume>(const VolumeSource& source, const std::filesystem::path& resolved_file)>
      load_volume;
  // Whether `transfer_function.preset` may name a file.
  bool allow_preset_files = true;
  // Turns a mesh file or a mesh's texture volume file, as written at `key`
  // (for example "meshes[0].file"), into the path to read. Empty: relative to
  // the scene's folder. A server passes its own to keep clients in its data folder.
  std::function<std::filesystem::path(const std::string& file, const std::string& key)> resolve_file;
  // Read a mesh file and a mesh's texture volume, at the path resolve_file
  // gave for what is written at `key`. Empty: read_mesh and read_volume. A
  // server passes its own to share them between sessions, as with volumes.
  std::function<std::shared_ptr<const TriangleMesh>(const std::filesystem::path& path, const std::string& key)>
      load_mesh;
  std::function<std::shared_ptr<const Volume>(const std::filesystem::path& path, const std::string& key)> load_texture;
};

// Parses scene JSON text; `base_dir` resolves relative paths.
Scene parse_scene(std::string_view json_text, const std::filesystem::path& base_dir,
                  const SceneParseOptions& options = {});

// The default volume loader: reads the file (IoError when missing) or makes
// the procedural volume, then applies the spacing/origin overrides.
std::shared_ptr<const Volume> load_scene_volume(const VolumeSource& source, const std::filesystem::path& resolved_file);

// Serialises a scene back to JSON v1 (volume by its VolumeSource).
std::string write_scene_json(const Scene& scene);

}  // namespace penumbra

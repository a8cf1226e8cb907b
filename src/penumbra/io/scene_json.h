#pragma once
// Scene JSON, version 1 (DESIGN.md 4). Strict: an unknown key, a value of the
// wrong type or out of range is an InvalidScene naming the key path (for
// example "lights[1].direction"); missing keys take the documented defaults
// (docs/scene-format.md). Relative file paths are relative to the scene file.
#include "penumbra/scene/scene.h"

#include <filesystem>
#include <string>
#include <string_view>

namespace penumbra {

// Reads and parses a scene file, loading its volume. IoError for an unreadable
// file, InvalidScene for bad content.
Scene load_scene(const std::filesystem::path& path);

// Parses scene JSON text; `base_dir` resolves relative paths and `origin`
// names the text in error messages.
Scene parse_scene(std::string_view json_text, const std::filesystem::path& base_dir);

// Serialises a scene back to JSON v1 (volume by its VolumeSource).
std::string write_scene_json(const Scene& scene);

}  // namespace penumbra

#pragma once
// The "meshes" section of scene JSON v1 (docs/scene-format.md), and the
// scene_json.cpp pieces it shares (io-internal).
#include "penumbra/io/json_reader.h"
#include "penumbra/io/scene_json.h"

#include <filesystem>
#include <string>
#include <vector>

namespace penumbra::json_reader {

TransferFunction read_transfer_function(const json& j, const std::string& section,
                                        const std::filesystem::path& base_dir, const SceneParseOptions& options);
json to_json(const TransferFunction& tf);

std::vector<MeshObject> read_meshes(const json& j, const std::filesystem::path& base_dir,
                                    const SceneParseOptions& options);
json meshes_to_json(const std::vector<MeshObject>& meshes);

}  // namespace penumbra::json_reader

#include "server/scene_update.h"

#include "penumbra/base/error.h"
#include "penumbra/io/scene_json.h"
#include "penumbra/techniques/registry.h"
#include "server/http_error.h"

#include <fmt/format.h>

namespace penumbra::server {
namespace {

using nlohmann::json;

void check_builtin_size(const json& volume, const SceneLimits& limits) {
  const auto size = volume.find("size");
  if (size == volume.end() || !size->is_array()) return;  // parse_scene reports malformed sizes
  for (const json& n : *size) {
    if (n.is_number_integer() && n.get<std::int64_t>() > limits.max_builtin_size) {
      throw HttpError(413, "volume.size",
                      fmt::format("this server makes builtin volumes of at most {} voxels per axis",
                                  limits.max_builtin_size));
    }
  }
}

void check_technique(const Scene& scene) {
  const TechniqueInfo* info = nullptr;
  try {
    info = &find_technique(scene.render().technique);
  } catch (const InvalidArgument& e) {
    throw InvalidScene("render.technique", e.what());
  }
  try {
    ParameterValues(info->parameters).apply(scene.render().params, true);
  } catch (const InvalidArgument& e) {
    throw InvalidScene("render.params." + e.name(), e.what());
  }
}

}  // namespace

ClientScene parse_client_scene(const json& scene_json, const DataDirectory& data, VolumeCache& cache,
                               const SceneLimits& limits) {
  if (!scene_json.is_object()) throw InvalidScene("(root)", "expected a scene object");
  ClientScene out;
  out.json = scene_json;
  if (const auto volume = scene_json.find("volume"); volume != scene_json.end() && volume->is_object()) {
    check_builtin_size(*volume, limits);
    out.volume_key = volume_key_of(scene_json);  // frames of one series share the cached volume
  }
  SceneParseOptions options;
  // A client could name any file on the server with a preset; the viewer
  // imports presets through POST /api/presets instead.
  options.allow_preset_files = false;
  options.load_volume = [&](const VolumeSource& source, const std::filesystem::path&) {
    return cache
        .get(out.volume_key,
             [&] {
               std::filesystem::path path;
               if (!source.file.empty()) path = data.resolve_volume(source.file, "volume.file");
               return LoadedVolume{load_scene_volume(source, path), source};
             })
        .volume;
  };
  // Mesh files and mesh texture volumes, like volumes, only from the data folder.
  options.resolve_file = [&](const std::string& file, const std::string& key) {
    return key.ends_with(".texture") ? data.resolve_volume(file, key) : data.resolve_mesh(file, key);
  };
  out.scene = parse_scene(scene_json.dump(), data.root(), options);
  check_technique(out.scene);
  return out;
}

}  // namespace penumbra::server

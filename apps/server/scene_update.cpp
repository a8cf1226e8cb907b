#include "server/scene_update.h"

#include "penumbra/base/error.h"
#include "penumbra/io/mesh_reader.h"
#include "penumbra/io/scene_json.h"
#include "penumbra/io/volume_reader.h"
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
    check_technique_prefixes(scene.render().params);
    ParameterValues(info->parameters).apply(scene.render().params, true, info->name);
  } catch (const InvalidArgument& e) {
    throw InvalidScene("render.params." + e.name(), e.what());
  }
}

// Runs a load of a file in the data folder; an IoError becomes a 422 that
// names the scene key and the file relative to the data folder, never the
// server's own paths.
template <class Load> auto in_data_folder(const DataDirectory& data, const std::string& key, const Load& load) {
  try {
    return load();
  } catch (const IoError& e) {
    throw HttpError(422, key, data.relative_message(e.what()));
  } catch (const OutOfMemoryBudget& e) {
    throw HttpError(413, key, data.relative_message(e.what()));
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
    return cache.volume(out.volume_key, [&] {
      if (source.file.empty()) return load_scene_volume(source, {});
      const std::filesystem::path path = data.resolve_volume(source.file, "volume.file");
      return in_data_folder(data, "volume.file", [&] { return load_scene_volume(source, path); });
    });
  };
  // Mesh files and mesh texture volumes, like volumes, only from the data
  // folder, and read once however many sessions show them.
  options.resolve_file = [&](const std::string& file, const std::string& key) {
    return key.ends_with(".texture") ? data.resolve_volume(file, key) : data.resolve_mesh(file, key);
  };
  options.load_mesh = [&](const std::filesystem::path& path, const std::string& key) {
    return cache.mesh(path.string(), [&] {
      return in_data_folder(data, key, [&] { return std::make_shared<const TriangleMesh>(read_mesh(path)); });
    });
  };
  options.load_texture = [&](const std::filesystem::path& path, const std::string& key) {
    return cache.texture(path.string(), [&] {
      return in_data_folder(data, key, [&]() -> std::shared_ptr<const Volume> { return read_volume(path); });
    });
  };
  out.scene = parse_scene(scene_json.dump(), data.root(), options);
  check_technique(out.scene);
  return out;
}

}  // namespace penumbra::server

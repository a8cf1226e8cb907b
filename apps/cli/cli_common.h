#pragma once
// Shared pieces of the penumbra subcommands: loading a scene (file or demo)
// with command-line overrides, and resolving technique parameters.
#include "penumbra/render/parameters.h"
#include "penumbra/render/technique.h"
#include "penumbra/scene/scene.h"

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace penumbra::cli {

struct SceneOptions {
  std::string scene_file;
  bool demo = false;
  std::string size;                 // "WxH"
  std::vector<std::string> params;  // "name=value"
};

// The scene named on the command line (or the demo scene), with --size applied.
Scene load_scene_for(const SceneOptions& options);

// Parameters for `info` from the scene's render.params (strictly when the
// technique is the scene's own, else only those it declares), then the
// command line's name=value pairs: strictly, or with `strict_cli` false only
// those the technique declares (bench runs several techniques with one list).
// "technique.name=value" applies to that technique only.
ParameterValues resolve_parameters(const Scene& scene, const TechniqueInfo& info,
                                   const std::vector<std::string>& cli_params, bool strict_cli = true);

// The folder of real volumes (../shared/data) if it can be found:
// $PENUMBRA_DATA_DIR, ./../shared/data, or beside the source tree.
std::optional<std::filesystem::path> find_data_dir();

// The built-in demo: the engine CT with shadows when the data folder is
// there, otherwise the procedural spheres.
Scene demo_scene();

// Warns on stderr when the scene has meshes and `info` does not draw them,
// naming the techniques that do ("penumbra: warning: T does not draw ...").
void warn_if_meshes_not_drawn(const Scene& scene, const TechniqueInfo& info);

// Parses "WxH" (e.g. "512x512"); throws InvalidArgument naming --size.
std::pair<int, int> parse_size(const std::string& text);

}  // namespace penumbra::cli

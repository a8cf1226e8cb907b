#include "cli_common.h"

#include "penumbra/base/error.h"
#include "penumbra/io/scene_json.h"
#include "penumbra/techniques/registry.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <charconv>
#include <cstdlib>

namespace penumbra::cli {

std::pair<int, int> parse_size(const std::string& text) {
  const auto x = text.find('x');
  int w = 0, h = 0;
  auto parse = [&](std::string_view s, int& out) {
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
    return ec == std::errc() && end == s.data() + s.size();
  };
  if (x == std::string::npos || !parse(std::string_view(text).substr(0, x), w) ||
      !parse(std::string_view(text).substr(x + 1), h) || w <= 0 || h <= 0 || w > 16384 || h > 16384) {
    throw InvalidArgument("--size", fmt::format("expected WIDTHxHEIGHT with sizes in 1..16384, got '{}'", text));
  }
  return {w, h};
}

Scene load_scene_for(const SceneOptions& options) {
  if (options.demo == !options.scene_file.empty()) {
    throw InvalidArgument("SCENE", "give a scene file or --demo (one of them)");
  }
  Scene scene = options.demo ? demo_scene() : load_scene(options.scene_file);
  if (!options.size.empty()) {
    const auto [w, h] = parse_size(options.size);
    RenderSettings r = scene.render();
    r.width = w;
    r.height = h;
    scene.set_render(r);
  }
  return scene;
}

ParameterValues resolve_parameters(const Scene& scene, const TechniqueInfo& info,
                                   const std::vector<std::string>& cli_params, bool strict_cli) {
  ParameterValues values(info.parameters);
  check_technique_prefixes(scene.render().params);
  const bool own = scene.render().technique == info.name;
  try {
    values.apply(scene.render().params, own, info.name);
  } catch (const InvalidArgument& e) {
    throw InvalidScene("render.params." + e.name(), fmt::format("technique '{}' refuses it: {}", info.name, e.what()));
  }
  for (const std::string& text : cli_params) {
    const auto eq = text.find('=');
    if (eq == std::string::npos || eq == 0) {
      throw InvalidArgument("--param", fmt::format("expected name=value, got '{}'", text));
    }
    std::string name = text.substr(0, eq);
    // "technique.name=value" applies only to that technique.
    if (const auto dot = name.find('.'); dot != std::string::npos) {
      if (name.substr(0, dot) != info.name) continue;
      name = name.substr(dot + 1);
    }
    if (!strict_cli && !info.parameters.find(name)) continue;
    ParameterValue value;
    try {
      value = info.parameters.at(name).parse(text.substr(eq + 1));
    } catch (const InvalidArgument&) {
      // A flat name another technique shares with other values (compare
      // checks that some technique accepts it).
      if (!strict_cli && text.substr(0, eq).find('.') == std::string::npos) continue;
      throw;
    }
    values.set(name, value);
  }
  return values;
}

std::optional<std::filesystem::path> find_data_dir() {
  std::vector<std::filesystem::path> candidates;
  if (const char* env = std::getenv("PENUMBRA_DATA_DIR")) candidates.emplace_back(env);
  candidates.emplace_back(std::filesystem::current_path() / ".." / "shared" / "data");
#ifdef PENUMBRA_SOURCE_DIR
  candidates.emplace_back(std::filesystem::path(PENUMBRA_SOURCE_DIR) / ".." / "shared" / "data");
#endif
  for (const auto& c : candidates) {
    std::error_code ec;
    if (std::filesystem::is_directory(c, ec)) return std::filesystem::weakly_canonical(c, ec);
  }
  return std::nullopt;
}

void warn_if_meshes_not_drawn(const Scene& scene, const TechniqueInfo& info) {
  if (scene.meshes().empty() || info.draws_meshes) return;
  std::vector<std::string> drawing;
  for (const TechniqueInfo& t : technique_registry()) {
    if (t.draws_meshes) drawing.push_back(t.name);
  }
  std::sort(drawing.begin(), drawing.end());
  fmt::print(stderr, "penumbra: warning: {} does not draw the scene's {} mesh(es); {} do\n", info.name,
             scene.meshes().size(), fmt::join(drawing, ", "));
}

}  // namespace penumbra::cli

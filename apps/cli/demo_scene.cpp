// The built-in demo scene (`penumbra render --demo`). The same scenes are in
// scenes/engine.json and scenes/spheres.json for users to edit.
#include "cli_common.h"

#include "penumbra/io/scene_json.h"

namespace penumbra::cli {
namespace {

constexpr const char* kEngineScene = R"json({
  "volume": {"file": "engine_256x256x128_uint8.nhdr"},
  "transfer_function": {
    "points": [[0.0, 0.0, 0.0, 0.0, 0.0], [0.30, 0.25, 0.35, 0.55, 0.0], [0.40, 0.35, 0.45, 0.65, 0.04],
               [0.65, 0.55, 0.6, 0.7, 0.08], [0.72, 0.95, 0.55, 0.25, 0.6], [1.0, 1.0, 0.9, 0.7, 0.9]],
    "range": "data"
  },
  "camera": {"eye": [330, -420, 260], "target": [0, 0, -10], "up": [0, 0, 1], "fov_deg": 30},
  "lights": [{"type": "directional", "direction": [0.45, 0.55, -1.0], "intensity": 1.6}],
  "material": {"shading": "phase", "ambient": 0.15},
  "render": {"width": 512, "height": 512, "step": 0.5, "technique": "shadow-rays"},
  "planes": [{"point": [0, 0, -70], "normal": [0, 0, 1], "color": [0.7, 0.7, 0.7]}],
  "background": [0.02, 0.02, 0.03]
})json";

constexpr const char* kSpheresScene = R"json({
  "volume": {"builtin": "spheres", "size": [96, 96, 96]},
  "transfer_function": {
    "points": [[0.0, 1.0, 1.0, 1.0, 0.0], [0.2, 0.9, 0.5, 0.2, 0.0], [0.3, 0.9, 0.5, 0.2, 0.3], [1.0, 1.0, 0.9, 0.8, 0.9]],
    "range": [0, 1]
  },
  "camera": {"eye": [110, -220, 120], "target": [0, 0, -10], "up": [0, 0, 1], "fov_deg": 30},
  "lights": [{"type": "directional", "direction": [0.4, 0.5, -1.0], "intensity": 1.6}],
  "material": {"shading": "phase", "ambient": 0.15},
  "render": {"width": 512, "height": 512, "step": 0.5, "technique": "shadow-rays"},
  "planes": [{"point": [0, 0, -55], "normal": [0, 0, 1], "color": [0.7, 0.7, 0.7]}],
  "background": [0.02, 0.02, 0.03]
})json";

}  // namespace

Scene demo_scene() {
  if (const auto data = find_data_dir(); data && std::filesystem::exists(*data / "engine_256x256x128_uint8.nhdr")) {
    return parse_scene(kEngineScene, *data);
  }
  return parse_scene(kSpheresScene, std::filesystem::current_path());
}

}  // namespace penumbra::cli

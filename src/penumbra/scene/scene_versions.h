#pragma once
// The scene's version counters (Scene::versions()): each part's counter
// grows when that part changes, so renderers rebuild (and backends re-upload)
// only what depends on the parts that changed.
#include <cstdint>

namespace penumbra {

struct SceneVersions {
  std::uint64_t data = 0;  // volume or time step
  std::uint64_t transfer_function = 0;
  std::uint64_t lights = 0;
  std::uint64_t camera = 0;
  std::uint64_t material = 0;  // material and background
  std::uint64_t geometry = 0;  // planes and clip planes
  std::uint64_t render = 0;    // image size, step, technique, parameters
  std::uint64_t meshes = 0;    // meshes, their placement and materials
};

}  // namespace penumbra

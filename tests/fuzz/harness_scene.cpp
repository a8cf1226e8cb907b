// Scene JSON through the whole loader (parse_scene with its volume, meshes,
// textures and preset files from the fixture folder), then a round trip
// through write_scene_json, and a prepare and an 8x8 render with the scene's
// technique and parameters.
#include "harness.h"

#include "penumbra/base/error.h"
#include "penumbra/base/memory_budget.h"
#include "penumbra/io/scene_json.h"
#include "penumbra/techniques/registry.h"

#include <fmt/format.h>

#include <algorithm>

namespace penumbra::fuzz {
namespace {

std::string_view as_text(Input input) { return {reinterpret_cast<const char*>(input.data()), input.size()}; }

// Scenes render at 8x8 on one thread with at most 16 paths per pixel, so
// that what is slow is the scene's doing (a step, a density, a technique
// parameter) and not the amount of work asked for.
// 64 MiB holds a builtin volume of 400^3 voxels and the techniques'
// structures for it; anything larger must fail the budget check cleanly.
constexpr std::uint64_t kSceneBudget = std::uint64_t(64) << 20;

}  // namespace

void fuzz_scene(Input input) {
  set_memory_budget_bytes(kSceneBudget);
  Scene scene = parse_scene(as_text(input), fixture_dir());
  // What the scene file says must survive being written and read again.
  try {
    (void)parse_scene(write_scene_json(scene), fixture_dir());
  } catch (const Error& e) {
    throw HarnessFailure(fmt::format("fuzz_scene: write_scene_json wrote a scene that does not read back: {}",
                                     e.what()));
  }
  RenderSettings render = scene.render();
  render.width = 8;
  render.height = 8;
  scene.set_render(render);
  const TechniqueInfo& info = find_technique(render.technique);
  ParameterValues params(info.parameters);
  params.apply(render.params, true);
  if (params.table().find("progress")) params.set("progress", false);
  // Paths per pixel bound the work as the image size does: 2^20 of them is
  // a legitimate request that takes minutes, not a hang.
  for (const char* name : {"spp", "min_spp"}) {
    if (params.table().find(name)) params.set(name, std::min(params.number(name), 16.0));
  }
  auto technique = info.create();
  technique->prepare(scene, params);
  Image image;
  technique->render(scene, image);
}

}  // namespace penumbra::fuzz

// penumbra bench SCENE.json [--technique T]... [--param k=v]... [--frames N]
// One JSON object per line per technique (DESIGN.md 4):
//   tf_change_ms   prepare() after the TF changes (median of 3)
//   light_move_ms  prepare() after every light moves by 2 degrees (median of 3)
//   frame_ms_*     prepare() + render() per frame, the camera orbiting 2
//                  degrees between frames (median and min of N)
//   aux_bytes      the technique's own memory
// plus samples_per_frame and samples_per_s (volume samples of viewing rays)
// and passes_per_frame (convolution's slabs; 0 for techniques that do not sweep),
// and lane_utilisation: samples over packet steps times lanes of the shared
// loop's viewing rays (1 on the scalar path; 0 where no step was counted).
#include "cli_common.h"
#include "commands.h"

#include "penumbra/backends/cpu/packets.h"
#include "penumbra/base/error.h"
#include "penumbra/base/parallel.h"
#include "penumbra/render/change_timing.h"
#include "penumbra/techniques/registry.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

namespace penumbra::cli {
namespace {

struct BenchOptions {
  SceneOptions scene;
  std::vector<std::string> techniques;
  int frames = 10;
};

void bench_technique(Scene scene, const TechniqueInfo& info, const BenchOptions& options) {
  const ParameterValues params = resolve_parameters(scene, info, options.scene.params, options.techniques.size() < 2);
  auto technique = info.create();
  Image image;
  technique->prepare(scene, params);
  technique->render(scene, image);  // warm-up

  const ChangeTimings changes = time_scene_changes(*technique, scene, params);

  std::vector<double> frame_ms;
  RenderStats stats;
  for (int f = 0; f < options.frames; ++f) {
    Camera camera = scene.camera();
    camera.orbit(2.0f, 0.0f);
    scene.set_camera(camera);
    const auto t0 = Clock::now();
    technique->prepare(scene, params);
    technique->render(scene, image, &stats);
    frame_ms.push_back(elapsed_ms(t0));
  }
  double total_ms = 0.0;
  for (double ms : frame_ms) total_ms += ms;
  const ivec3 d = scene.volume().dims();
  const std::string volume = scene.volume_source().builtin.empty() ? scene.volume_source().file
                                                                   : scene.volume_source().builtin;
  fmt::print(
      "{{\"technique\": \"{}\", \"volume\": \"{}\", \"dims\": [{}, {}, {}], \"image\": [{}, {}], "
      "\"tf_change_ms\": {:.3f}, \"light_move_ms\": {:.3f}, \"frame_ms_median\": {:.3f}, \"frame_ms_min\": {:.3f}, "
      "\"aux_bytes\": {}, \"threads\": {}, \"simd\": \"{}\", \"device\": \"{}\", \"samples_per_frame\": {}, \"samples_per_s\": {:.4g}, "
      "\"samples_per_s_per_thread\": {:.4g}, "
      "\"passes_per_frame\": {}, \"lane_utilisation\": {:.3f}}}\n",
      info.name, volume, d.x, d.y, d.z, scene.render().width, scene.render().height, changes.tf_change_ms,
      changes.light_move_ms, median(frame_ms), *std::min_element(frame_ms.begin(), frame_ms.end()),
      technique->aux_bytes(), thread_count(), to_string(stats.simd), to_string(stats.device), stats.samples / std::uint64_t(options.frames),
      total_ms > 0.0 ? double(stats.samples) / (total_ms * 1e-3) : 0.0,
      total_ms > 0.0 ? double(stats.samples) / (total_ms * 1e-3) / thread_count() : 0.0,
      stats.passes / std::uint64_t(options.frames),
      stats.steps > 0 ? double(stats.samples) / (double(stats.steps) * double(simd_width(stats.simd))) : 0.0);
  std::fflush(stdout);
}

void run_bench(const BenchOptions& options) {
  if (options.frames < 1) throw InvalidArgument("--frames", "must be at least 1");
  const Scene scene = load_scene_for(options.scene);
  std::vector<std::string> names = options.techniques;
  if (names.empty()) names.push_back(scene.render().technique);
  std::vector<const TechniqueInfo*> infos;
  for (const std::string& n : names) infos.push_back(&find_technique(n));  // all names checked before any run
  // Every --param must be declared by at least one of the techniques.
  for (const std::string& p : options.scene.params) {
    std::string name = p.substr(0, p.find('='));
    if (const auto dot = name.find('.'); dot != std::string::npos) name = name.substr(dot + 1);
    bool known = false;
    for (const TechniqueInfo* info : infos) known = known || info->parameters.find(name);
    if (!known) throw InvalidArgument(name, "no technique being timed has this parameter (see penumbra techniques)");
  }
  for (const TechniqueInfo* info : infos) bench_technique(scene, *info, options);
}

}  // namespace

void add_bench_command(CLI::App& app) {
  auto options = std::make_shared<BenchOptions>();
  CLI::App* cmd = app.add_subcommand("bench", "time TF change, light move and frames; one JSON line per technique");
  cmd->add_option("scene", options->scene.scene_file, "scene JSON file");
  cmd->add_flag("--demo", options->scene.demo, "benchmark the built-in demo scene");
  cmd->add_option("--technique", options->techniques, "technique to time (repeatable; default: the scene's)");
  cmd->add_option("--param", options->scene.params, "technique parameter name=value or technique.name=value");
  cmd->add_option("--frames", options->frames, "frames for the median (default 10)");
  cmd->add_option("--size", options->scene.size, "image size WIDTHxHEIGHT (default: the scene's)");
  cmd->callback([options] { run_bench(*options); });
}

}  // namespace penumbra::cli

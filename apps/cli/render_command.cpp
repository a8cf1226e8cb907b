// penumbra render SCENE.json -o out.png [--technique T] [--param k=v]... [--size WxH]
//                 [--frames N [--time-step DT]]
// penumbra render --demo
// With --frames N the meshes' animated detail (detail.time) advances by DT
// per frame and frame i is written to out-000i.png (Patel et al. 2013's
// animated detail; the volume stays as it is).
#include "cli_common.h"
#include "commands.h"

#include "penumbra/base/error.h"
#include "penumbra/io/image_io.h"
#include "penumbra/techniques/registry.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <vector>

namespace penumbra::cli {
namespace {

struct RenderOptions {
  SceneOptions scene;
  std::string output;
  std::string technique;
  int frames = 1;
  double time_step = 0.04;
};

// out.png -> out-0003.png for frame 3 of a sequence.
std::filesystem::path frame_path(const std::filesystem::path& output, int frame) {
  std::filesystem::path p = output;
  p.replace_filename(fmt::format("{}-{:04d}{}", output.stem().string(), frame, output.extension().string()));
  return p;
}

// Each time-dependent mesh detail at its scene time plus `offset`.
void advance_detail(Scene& scene, const std::vector<MeshObject>& start, double offset) {
  std::vector<MeshObject> meshes = start;
  for (MeshObject& m : meshes) {
    if (m.material.detail.time_dependent) m.material.detail.fractal.time += float(offset);
  }
  scene.set_meshes(std::move(meshes));
}

void write_image(const std::filesystem::path& path, const Image& image) {
  const std::string ext = path.extension().string();
  if (ext == ".png") {
    write_png(path, image);
  } else if (ext == ".exr") {
    write_exr(path, image);
  } else {
    throw InvalidArgument("-o", fmt::format("'{}': the output must end in .png or .exr", path.string()));
  }
}

void run_render(const RenderOptions& options) {
  Scene scene = load_scene_for(options.scene);
  const std::string technique = options.technique.empty() ? scene.render().technique : options.technique;
  const TechniqueInfo& info = find_technique(technique);
  const ParameterValues params = resolve_parameters(scene, info, options.scene.params);
  std::string output = options.output;
  if (output.empty()) {
    if (!options.scene.demo) throw InvalidArgument("-o", "an output file is required (.png or .exr)");
    output = "penumbra-demo.png";
  }
  if (options.frames < 1 || options.frames > 100000) {
    throw InvalidArgument("--frames", fmt::format("{} frames: give 1 to 100000", options.frames));
  }
  if (!std::isfinite(options.time_step)) throw InvalidArgument("--time-step", "must be a finite number");
  const std::vector<MeshObject> start = scene.meshes();
  if (options.frames > 1 && std::none_of(start.begin(), start.end(), [](const MeshObject& m) {
        return m.material.detail.time_dependent;
      })) {
    throw InvalidArgument("--frames", "the scene has no animated detail to advance (a mesh whose detail has a "
                                      "\"time\" key)");
  }
  warn_if_meshes_not_drawn(scene, info);
  if (options.frames > 1) {
    const std::string ext = std::filesystem::path(output).extension().string();
    if (ext != ".png" && ext != ".exr") {
      throw InvalidArgument("-o", fmt::format("'{}': the output must end in .png or .exr", output));
    }
  }
  using Clock = std::chrono::steady_clock;
  const auto ms = [](auto d) { return std::chrono::duration<double, std::milli>(d).count(); };
  auto t = info.create();
  for (int frame = 0; frame < options.frames; ++frame) {
    if (options.frames > 1) advance_detail(scene, start, double(frame) * options.time_step);
    const auto t0 = Clock::now();
    t->prepare(scene, params);
    const auto t1 = Clock::now();
    Image image;
    RenderStats stats;
    t->render(scene, image, &stats);
    const auto t2 = Clock::now();
    const std::filesystem::path path = options.frames > 1 ? frame_path(output, frame) : std::filesystem::path(output);
    write_image(path, image);
    fmt::print(stderr, "{}: {} {}x{}, prepare {:.1f} ms, frame {:.1f} ms, {:.2f} M samples\n",
               scene.volume().source(), info.name, image.width(), image.height(), ms(t1 - t0), ms(t2 - t1),
               double(stats.samples) * 1e-6);
    std::fflush(stderr);
    fmt::print("{}\n", std::filesystem::absolute(path).lexically_normal().string());
  }
}

}  // namespace

void add_render_command(CLI::App& app) {
  auto options = std::make_shared<RenderOptions>();
  CLI::App* cmd = app.add_subcommand("render", "render a scene to a PNG (8-bit sRGB) or EXR (linear float) image");
  cmd->add_option("scene", options->scene.scene_file, "scene JSON file");
  cmd->add_flag("--demo", options->scene.demo,
                "render the built-in demo (the engine CT from ../shared/data, else procedural spheres)");
  cmd->add_option("-o,--output", options->output, "output image (.png or .exr)");
  cmd->add_option("--technique", options->technique, "technique name (default: the scene's render.technique)");
  cmd->add_option("--param", options->scene.params, "technique parameter name=value (repeatable)");
  cmd->add_option("--size", options->scene.size, "image size WIDTHxHEIGHT (default: the scene's)");
  cmd->add_option("--frames", options->frames,
                  "render this many frames, the meshes' animated detail advancing by --time-step per frame, "
                  "to OUTPUT-0000.png, OUTPUT-0001.png, ...");
  cmd->add_option("--time-step", options->time_step, "detail time between frames (default 0.04)");
  cmd->callback([options] { run_render(*options); });
}

}  // namespace penumbra::cli

// penumbra render SCENE.json -o out.png [--technique T] [--param k=v]... [--size WxH]
// penumbra render --demo
#include "cli_common.h"
#include "commands.h"

#include "penumbra/base/error.h"
#include "penumbra/io/image_io.h"
#include "penumbra/techniques/registry.h"

#include <fmt/format.h>

#include <chrono>
#include <memory>

namespace penumbra::cli {
namespace {

struct RenderOptions {
  SceneOptions scene;
  std::string output;
  std::string technique;
};

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
  if (!scene.meshes().empty() && !info.draws_meshes) {
    fmt::print(stderr,
               "penumbra: warning: {} does not draw the scene's {} mesh(es); convolution and pathtrace do\n", info.name,
               scene.meshes().size());
  }
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  auto t = info.create();
  t->prepare(scene, params);
  const auto t1 = Clock::now();
  Image image;
  RenderStats stats;
  t->render(scene, image, &stats);
  const auto t2 = Clock::now();
  write_image(output, image);
  const auto ms = [](auto d) { return std::chrono::duration<double, std::milli>(d).count(); };
  fmt::print(stderr, "{}: {} {}x{}, prepare {:.1f} ms, frame {:.1f} ms, {:.2f} M samples\n",
             scene.volume().source(), info.name, image.width(), image.height(), ms(t1 - t0), ms(t2 - t1),
             double(stats.samples) * 1e-6);
  std::fflush(stderr);
  fmt::print("{}\n", std::filesystem::absolute(output).lexically_normal().string());
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
  cmd->callback([options] { run_render(*options); });
}

}  // namespace penumbra::cli

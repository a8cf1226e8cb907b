// penumbra compare SCENE.json --techniques a,b,... [--reference pathtrace | --reference-image REF.exr]
//                  [--param technique.k=v]... [--size WxH] [--frames N] [--de-max X] -o DIR
// Renders the scene with every technique and the reference and writes to DIR
// (docs/comparison-report.md):
//   <name>.png, <name>.exr       each technique's image (reference.* for the reference)
//   <name>-de.png                CIEDE2000 against the reference, false colour with a colour bar
//   <name>-luminance.png         signed luminance difference (blue: too dark, red: too bright)
//   reference-noise.png          the pathtrace reference's own standard error in dE
//   grid.png                     labelled side by side: images above, differences below
//   report.json, report.md       per technique: RMSE, PSNR, SSIM, mean and p99 dE, timings, aux_bytes
// The renders, metrics, timings and report.json come from
// techniques/comparison.h; this file checks the options and writes the files.
#include "cli_common.h"
#include "commands.h"

#include "penumbra/analysis/color_bar.h"
#include "penumbra/analysis/comparison_grid.h"
#include "penumbra/analysis/difference_image.h"
#include "penumbra/analysis/image_metrics.h"
#include "penumbra/base/error.h"
#include "penumbra/io/image_io.h"
#include "penumbra/techniques/comparison.h"
#include "penumbra/techniques/registry.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <memory>

namespace penumbra::cli {
namespace {

struct CompareOptions {
  SceneOptions scene;
  std::vector<std::string> techniques;
  std::string reference = "pathtrace";
  std::string reference_image;
  std::string output;
  int frames = 3;
  float max_delta_e = 10.0f;
};

// Every --param must name a technique being rendered (technique.k=v) and a
// parameter it declares, or (k=v) a parameter one of them declares and
// accepts the value of (techniques that share a name with other values skip
// it: resolve_parameters).
void check_parameters(const std::vector<std::string>& params, const std::vector<const TechniqueInfo*>& infos) {
  for (const std::string& text : params) {
    std::string name = text.substr(0, text.find('='));
    std::string owner;
    if (const auto dot = name.find('.'); dot != std::string::npos) {
      owner = name.substr(0, dot);
      name = name.substr(dot + 1);
    }
    bool declared = false, accepted = false, owner_found = owner.empty();
    std::string refusal;
    const std::string value = text.find('=') == std::string::npos ? "" : text.substr(text.find('=') + 1);
    for (const TechniqueInfo* info : infos) {
      if (!owner.empty() && info->name != owner) continue;
      owner_found = true;
      const ParameterSpec* spec = info->parameters.find(name);
      if (!spec) continue;
      declared = true;
      try {
        spec->parse(value);
        accepted = true;
      } catch (const InvalidArgument& e) {
        if (refusal.empty()) refusal = fmt::format("{} refuses it: {}", info->name, e.what());
      }
    }
    if (!owner_found) {
      throw InvalidArgument("--param", fmt::format("'{}': {} is not among the techniques compared", text, owner));
    }
    if (!declared) {
      throw InvalidArgument(name, fmt::format("no technique compared declares this parameter (in '{}'; see penumbra "
                                              "techniques)",
                                              text));
    }
    if (!accepted) throw InvalidArgument(name, fmt::format("'{}': {}", text, refusal));
  }
}

Image false_colour(const std::vector<float>& values, int width, int height, float max_value, const char* title) {
  Image image(width, height);
  for (std::size_t i = 0; i < values.size(); ++i) {
    image.data()[i] = vec4(map_color(ColorMap::viridis, values[i] / max_value), 1.0f);
  }
  return append_color_bar(image, ColorBar{ColorMap::viridis, 0.0f, max_value, title});
}

void write_reports(const std::filesystem::path& dir, const CompareOptions& options, const Scene& scene,
                   const Comparison& comparison) {
  const TechniqueRun& reference = comparison.reference;
  const std::string reference_name = options.reference_image.empty() ? reference.name : options.reference_image;
  const std::string json = comparison_report_json(comparison, options.scene.scene_file, reference_name,
                                                  scene.render().width, scene.render().height);
  std::string md = fmt::format("# Technique comparison: {}\n\n", options.scene.scene_file);
  md += fmt::format("{}x{} pixels; reference: {}", scene.render().width, scene.render().height, reference_name);
  if (comparison.reference_rendered) md += fmt::format(" ({:.0f} ms)", reference.timings.frame_ms);
  if (const auto& noise = comparison.noise) {
    md += fmt::format(", its own noise (one standard error) {:.2f} dE mean, {:.2f} dE p99: differences below this are "
                      "not resolved",
                      noise->mean, noise->p99);
  }
  md += ".\n\n![comparison](grid.png)\n\n";
  md += "| technique | RMSE | PSNR dB | SSIM | mean dE | p99 dE | tf_change ms | light_move ms | frame ms | aux MB | device |\n";
  md += "|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const ComparedTechnique& r : comparison.techniques) {
    const TechniqueTimings& t = r.run.timings;
    md += fmt::format("| {} | {:.4f} | {:.2f} | {:.4f} | {:.2f} | {:.2f} | {:.1f} | {:.1f} | {:.1f} | {:.2f} | {} |\n",
                      r.run.name, r.metrics.rmse, r.metrics.psnr, r.metrics.ssim, r.metrics.mean_de,
                      r.metrics.p99_de, t.tf_change_ms, t.light_move_ms, t.frame_ms, double(t.aux_bytes) / 1048576.0, to_string(t.device));
  }
  md += "\nPer technique: `<name>.png`/`.exr` (linear), `<name>-de.png` (CIEDE2000 against the reference), "
        "`<name>-luminance.png` (blue: darker than the reference, red: brighter). Metrics: "
        "docs/comparison-report.md.\n";
  for (const auto& [file, text] : {std::pair{"report.json", json}, std::pair{"report.md", md}}) {
    std::ofstream out(dir / file);
    out << text;
    if (!out) throw IoError((dir / file).string(), "cannot write");
  }
}

// At most this many cells per grid row, so a comparison of many techniques
// stays readable.
constexpr int kGridColumns = 5;

// The cells of a grid with each image above its difference image: rows of
// up to kGridColumns images, each followed by the row of their differences
// (the last pair of rows padded with empty cells).
std::vector<LabeledImage> interleave_rows(std::vector<LabeledImage> images, std::vector<LabeledImage> differences) {
  std::vector<LabeledImage> cells;
  for (std::size_t first = 0; first < images.size(); first += kGridColumns) {
    for (auto* row : {&images, &differences}) {
      for (std::size_t i = first; i < first + kGridColumns; ++i) {
        cells.push_back(i < row->size() ? std::move((*row)[i]) : LabeledImage{});
      }
    }
  }
  return cells;
}

void write_image_pair(const std::filesystem::path& dir, const std::string& stem, const Image& image) {
  write_png(dir / (stem + ".png"), image);
  write_exr(dir / (stem + ".exr"), image);
}

void run_compare(const CompareOptions& options) {
  if (options.frames < 1) throw InvalidArgument("--frames", "must be at least 1");
  if (!(options.max_delta_e > 0.0f) || !std::isfinite(options.max_delta_e)) {
    throw InvalidArgument("--de-max", "must be positive and finite");
  }
  if (options.output.empty()) throw InvalidArgument("-o", "an output folder is required");
  const Scene scene = load_scene_for(options.scene);
  // Every name is checked against the registry before anything renders.
  std::vector<const TechniqueInfo*> infos;
  for (const std::string& name : options.techniques) {
    if (name == "all") {
      for (const TechniqueInfo& info : technique_registry()) {
        if (info.name != options.reference) infos.push_back(&info);
      }
    } else {
      infos.push_back(&find_technique(name));
    }
  }
  if (infos.empty()) throw InvalidArgument("--techniques", "name at least one technique (or all)");
  const TechniqueInfo* reference_info = options.reference_image.empty() ? &find_technique(options.reference) : nullptr;
  std::vector<const TechniqueInfo*> involved = infos;
  if (reference_info) involved.push_back(reference_info);
  check_parameters(options.scene.params, involved);
  // Every parameter value and the stored reference are checked before
  // anything is written or rendered.
  ComparisonRequest request;
  request.techniques = infos;
  request.frames = options.frames;
  for (const TechniqueInfo* info : infos) {
    request.params.push_back(resolve_parameters(scene, *info, options.scene.params, false));
  }
  request.reference = reference_info;
  if (reference_info) {
    request.reference_params = resolve_parameters(scene, *reference_info, options.scene.params, false);
  } else {
    request.reference_image = read_exr(options.reference_image);
    if (request.reference_image.width() != scene.render().width ||
        request.reference_image.height() != scene.render().height) {
      throw InvalidArgument("--reference-image",
                            fmt::format("'{}' is {}x{} but the scene renders {}x{} (use --size)",
                                        options.reference_image, request.reference_image.width(),
                                        request.reference_image.height(), scene.render().width,
                                        scene.render().height));
    }
  }

  const std::filesystem::path dir(options.output);
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir)) throw IoError(dir.string(), "cannot create the output folder");

  if (reference_info) warn_if_meshes_not_drawn(scene, *reference_info);
  for (const TechniqueInfo* info : infos) warn_if_meshes_not_drawn(scene, *info);
  const Comparison comparison = compare_techniques(scene, request, [](const std::string& name, bool reference) {
    fmt::print(stderr, "{}: {}\n", reference ? "reference" : "technique", name);
  });
  const TechniqueRun& reference = comparison.reference;
  write_image_pair(dir, "reference", reference.image);

  std::vector<LabeledImage> top{{reference.image, "reference\n" + (reference_info ? reference.name : "(file)")}};
  std::vector<LabeledImage> bottom;
  if (const auto& noise = comparison.noise) {
    write_exr(dir / "reference-stderr.exr", reference.estimate->standard_error);
    Image noise_image = false_colour(comparison.noise_de, reference.image.width(), reference.image.height(),
                                     options.max_delta_e, "noise dE");
    write_png(dir / "reference-noise.png", noise_image);
    bottom.push_back(
        {std::move(noise_image), fmt::format("reference noise\ndE {:.2f}, p99 {:.2f}", noise->mean, noise->p99)});
  } else {
    bottom.push_back({Image(), "reference noise\nnot known"});
  }

  for (const ComparedTechnique& r : comparison.techniques) {
    write_image_pair(dir, r.run.name, r.run.image);
    Image de = make_delta_e_image(r.run.image, reference.image, options.max_delta_e);
    write_png(dir / (r.run.name + "-de.png"), de);
    write_png(dir / (r.run.name + "-luminance.png"), make_signed_luminance_image(r.run.image, reference.image));
    top.push_back({r.run.image, fmt::format("{}\n{:.1f} ms/frame", r.run.name, r.run.timings.frame_ms)});
    bottom.push_back({std::move(de), fmt::format("dE {:.2f}, p99 {:.2f}\nPSNR {:.1f} SSIM {:.3f}", r.metrics.mean_de,
                                                 r.metrics.p99_de, r.metrics.psnr, r.metrics.ssim)});
  }
  write_png(dir / "grid.png", make_comparison_grid(interleave_rows(std::move(top), std::move(bottom)), kGridColumns));
  write_reports(dir, options, scene, comparison);
  for (const ComparedTechnique& r : comparison.techniques) {
    fmt::print("{}: mean dE {:.2f}, p99 dE {:.2f}, PSNR {:.2f} dB, SSIM {:.4f}, {:.1f} ms/frame\n", r.run.name,
               r.metrics.mean_de, r.metrics.p99_de, r.metrics.psnr, r.metrics.ssim, r.run.timings.frame_ms);
  }
  fmt::print("{}\n", std::filesystem::absolute(dir / "report.md").string());
}

}  // namespace

void add_compare_command(CLI::App& app) {
  auto options = std::make_shared<CompareOptions>();
  CLI::App* cmd = app.add_subcommand(
      "compare", "render a scene with several techniques and measure each against a reference (images, report)");
  cmd->add_option("scene", options->scene.scene_file, "scene JSON file");
  cmd->add_flag("--demo", options->scene.demo, "compare on the built-in demo scene");
  cmd->add_option("--techniques", options->techniques, "techniques to compare, comma-separated, or all")
      ->delimiter(',')
      ->required();
  cmd->add_option("--reference", options->reference, "technique rendering the reference (default pathtrace)");
  cmd->add_option("--reference-image", options->reference_image,
                  "compare against this EXR instead of rendering a reference (e.g. scenes/reference/*.exr)");
  cmd->add_option("--param", options->scene.params,
                  "parameter technique.name=value (or name=value for every technique declaring it); repeatable");
  cmd->add_option("--size", options->scene.size, "image size WIDTHxHEIGHT (default: the scene's)");
  cmd->add_option("--frames", options->frames, "frames timed per technique for frame_ms (default 3)");
  cmd->add_option("--de-max", options->max_delta_e, "dE at the top of the difference images' colour bar (default 10)");
  cmd->add_option("-o,--output", options->output, "output folder")->required();
  cmd->callback([options] { run_compare(*options); });
}

}  // namespace penumbra::cli

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
// Timings as `penumbra bench` takes them: tf_change_ms and light_move_ms are
// medians of 3 prepares after a TF nudge / a 2-degree light move, frame_ms
// the median of --frames prepare + render of the unchanged scene (after one
// untimed prepare that builds the technique's structures).
#include "cli_common.h"
#include "commands.h"
#include "timing.h"

#include "penumbra/analysis/color_bar.h"
#include "penumbra/analysis/comparison_grid.h"
#include "penumbra/analysis/difference_image.h"
#include "penumbra/analysis/image_metrics.h"
#include "penumbra/base/error.h"
#include "penumbra/io/image_io.h"
#include "penumbra/techniques/pathtrace/pathtrace.h"
#include "penumbra/techniques/registry.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <memory>
#include <optional>

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

struct Timings {
  double tf_change_ms = 0.0;
  double light_move_ms = 0.0;
  double frame_ms = 0.0;
  std::uint64_t aux_bytes = 0;
};

struct Rendered {
  std::string name;
  ParameterValues params;
  Image image;
  Timings timings;
  std::optional<PathTraceEstimate> estimate;  // when the technique is pathtrace
};

struct Result {
  Rendered rendered;
  ImageComparison metrics;
};

Rendered render_technique(const Scene& scene, const TechniqueInfo& info, const ParameterValues& params, int frames) {
  Rendered r{info.name, params, Image{}, Timings{}, std::nullopt};
  auto technique = info.create();
  // The first prepare builds the technique's structures; that cost is
  // tf_change_ms / light_move_ms, not part of a frame of an unchanged scene.
  technique->prepare(scene, params);
  std::vector<double> frame_ms;
  for (int f = 0; f < frames; ++f) {
    Image image;
    const auto t0 = Clock::now();
    technique->prepare(scene, params);
    technique->render(scene, image);
    frame_ms.push_back(elapsed_ms(t0));
    if (f == 0) r.image = std::move(image);
  }
  r.timings.frame_ms = median(frame_ms);
  if (const PathTraceEstimate* e = pathtrace_estimate(*technique)) r.estimate = *e;
  r.timings.aux_bytes = technique->aux_bytes();
  Scene changed = scene;
  const ChangeTimings changes = time_scene_changes(*technique, changed, params);
  r.timings.tf_change_ms = changes.tf_change_ms;
  r.timings.light_move_ms = changes.light_move_ms;
  return r;
}

// Every --param must name a technique being rendered (technique.k=v) and a
// parameter it declares, or (k=v) a parameter one of them declares.
void check_parameters(const std::vector<std::string>& params, const std::vector<const TechniqueInfo*>& infos) {
  for (const std::string& text : params) {
    std::string name = text.substr(0, text.find('='));
    std::string owner;
    if (const auto dot = name.find('.'); dot != std::string::npos) {
      owner = name.substr(0, dot);
      name = name.substr(dot + 1);
    }
    bool declared = false, owner_found = owner.empty();
    for (const TechniqueInfo* info : infos) {
      if (!owner.empty() && info->name != owner) continue;
      owner_found = true;
      declared = declared || info->parameters.find(name) != nullptr;
    }
    if (!owner_found) {
      throw InvalidArgument("--param", fmt::format("'{}': {} is not among the techniques compared", text, owner));
    }
    if (!declared) {
      throw InvalidArgument(name, fmt::format("no technique compared declares this parameter (in '{}'; see penumbra "
                                              "techniques)",
                                              text));
    }
  }
}

// The pathtrace reference's noise in CIEDE2000 per pixel: the colour
// difference one standard error makes, all channels moved together (the
// larger of + and -). The channels of a path share its geometry and differ
// only by albedo and light colour, so their errors are nearly perfectly
// correlated; moving them one at a time would invent chroma noise.
std::vector<float> noise_delta_e(const Image& mean, const Image& standard_error) {
  std::vector<float> out(mean.pixel_count());
  auto lab = [](vec3 c) { return srgb_linear_to_lab(glm::clamp(c, vec3(0.0f), vec3(1.0f))); };
  for (std::size_t i = 0; i < out.size(); ++i) {
    const vec3 m(mean.pixels()[i]);
    const vec3 se(standard_error.pixels()[i]);
    const Lab centre = lab(m);
    out[i] = float(std::max(delta_e_2000(centre, lab(m + se)), delta_e_2000(centre, lab(m - se))));
  }
  return out;
}

Image false_colour(const std::vector<float>& values, int width, int height, float max_value, const char* title) {
  Image image(width, height);
  for (std::size_t i = 0; i < values.size(); ++i) {
    image.data()[i] = vec4(map_color(ColorMap::viridis, values[i] / max_value), 1.0f);
  }
  return append_color_bar(image, ColorBar{ColorMap::viridis, 0.0f, max_value, title});
}

std::string json_string(std::string_view s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      out += fmt::format("\\u{:04x}", int(c));
    } else {
      out += c;
    }
  }
  return out + "\"";
}

// JSON has no infinities or NaN: those are null (PSNR of identical images).
std::string json_number(double x) { return std::isfinite(x) ? fmt::format("{:.6g}", x) : "null"; }

std::string json_parameters(const ParameterValues& values) {
  std::vector<std::string> fields;
  for (const ParameterSpec& spec : values.table().specs()) {
    const ParameterValue& v = values.value(spec.name);
    std::string text;
    if (const double* d = std::get_if<double>(&v)) text = json_number(*d);
    else if (const bool* b = std::get_if<bool>(&v)) text = *b ? "true" : "false";
    else text = json_string(std::get<std::string>(v));
    fields.push_back(fmt::format("{}: {}", json_string(spec.name), text));
  }
  return "{" + fmt::format("{}", fmt::join(fields, ", ")) + "}";
}

struct NoiseSummary {
  double mean = 0.0;
  double median = 0.0;
  double p99 = 0.0;
  double max = 0.0;
};

void write_reports(const std::filesystem::path& dir, const CompareOptions& options, const Scene& scene,
                   const Rendered& reference, const std::optional<NoiseSummary>& noise,
                   const std::vector<Result>& results) {
  const std::string reference_name = options.reference_image.empty() ? reference.name : options.reference_image;
  std::string json = "{\n";
  json += fmt::format("  \"scene\": {},\n  \"image\": [{}, {}],\n", json_string(options.scene.scene_file),
                      scene.render().width, scene.render().height);
  json += fmt::format("  \"reference\": {{\"source\": {}", json_string(reference_name));
  if (options.reference_image.empty()) {
    json += fmt::format(", \"technique\": {}, \"params\": {}, \"frame_ms\": {}", json_string(reference.name),
                        json_parameters(reference.params), json_number(reference.timings.frame_ms));
  }
  if (reference.estimate) json += fmt::format(", \"paths\": {}", reference.estimate->paths);
  if (noise) {
    json += fmt::format(", \"noise_de_mean\": {}, \"noise_de_median\": {}, \"noise_de_p99\": {}, \"noise_de_max\": {}",
                        json_number(noise->mean), json_number(noise->median), json_number(noise->p99),
                        json_number(noise->max));
  }
  json += "},\n  \"techniques\": [\n";
  for (std::size_t i = 0; i < results.size(); ++i) {
    const Result& r = results[i];
    const Timings& t = r.rendered.timings;
    json += fmt::format(
        "    {{\"technique\": {}, \"params\": {}, \"rmse\": {}, \"psnr\": {}, \"ssim\": {}, \"mean_de\": {}, "
        "\"p99_de\": {}, \"max_de\": {}, \"tf_change_ms\": {}, \"light_move_ms\": {}, \"frame_ms\": {}, "
        "\"aux_bytes\": {}}}{}\n",
        json_string(r.rendered.name), json_parameters(r.rendered.params), json_number(r.metrics.rmse),
        json_number(r.metrics.psnr), json_number(r.metrics.ssim), json_number(r.metrics.mean_de),
        json_number(r.metrics.p99_de), json_number(r.metrics.max_de), json_number(t.tf_change_ms),
        json_number(t.light_move_ms), json_number(t.frame_ms), t.aux_bytes, i + 1 < results.size() ? "," : "");
  }
  json += "  ]\n}\n";

  std::string md = fmt::format("# Technique comparison: {}\n\n", options.scene.scene_file);
  md += fmt::format("{}x{} pixels; reference: {}", scene.render().width, scene.render().height, reference_name);
  if (options.reference_image.empty()) md += fmt::format(" ({:.0f} ms)", reference.timings.frame_ms);
  if (noise) {
    md += fmt::format(", its own noise (one standard error) {:.2f} dE mean, {:.2f} dE p99: differences below this are "
                      "not resolved",
                      noise->mean, noise->p99);
  }
  md += ".\n\n![comparison](grid.png)\n\n";
  md += "| technique | RMSE | PSNR dB | SSIM | mean dE | p99 dE | tf_change ms | light_move ms | frame ms | aux MB |\n";
  md += "|---|---|---|---|---|---|---|---|---|---|\n";
  for (const Result& r : results) {
    const Timings& t = r.rendered.timings;
    md += fmt::format("| {} | {:.4f} | {:.2f} | {:.4f} | {:.2f} | {:.2f} | {:.1f} | {:.1f} | {:.1f} | {:.2f} |\n",
                      r.rendered.name, r.metrics.rmse, r.metrics.psnr, r.metrics.ssim, r.metrics.mean_de,
                      r.metrics.p99_de, t.tf_change_ms, t.light_move_ms, t.frame_ms, double(t.aux_bytes) / 1048576.0);
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
  std::vector<ParameterValues> params;
  for (const TechniqueInfo* info : infos) {
    params.push_back(resolve_parameters(scene, *info, options.scene.params, false));
  }
  Rendered reference;
  if (reference_info) {
    reference.params = resolve_parameters(scene, *reference_info, options.scene.params, false);
  } else {
    reference.name = "reference";
    reference.image = read_exr(options.reference_image);
    if (reference.image.width() != scene.render().width || reference.image.height() != scene.render().height) {
      throw InvalidArgument("--reference-image",
                            fmt::format("'{}' is {}x{} but the scene renders {}x{} (use --size)",
                                        options.reference_image, reference.image.width(), reference.image.height(),
                                        scene.render().width, scene.render().height));
    }
  }

  const std::filesystem::path dir(options.output);
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir)) throw IoError(dir.string(), "cannot create the output folder");

  if (reference_info) {
    fmt::print(stderr, "reference: {}\n", reference_info->name);
    reference = render_technique(scene, *reference_info, reference.params, 1);
  }
  write_image_pair(dir, "reference", reference.image);

  std::vector<LabeledImage> top{{reference.image, "reference\n" + (reference_info ? reference.name : "(file)")}};
  std::vector<LabeledImage> bottom;
  std::optional<NoiseSummary> noise;
  if (reference.estimate) {
    write_exr(dir / "reference-stderr.exr", reference.estimate->standard_error);
    const std::vector<float> noise_de = noise_delta_e(reference.image, reference.estimate->standard_error);
    const DeltaEStats s = delta_e_stats(noise_de);
    noise = NoiseSummary{s.mean, s.median, s.p99, s.max};
    Image noise_image = false_colour(noise_de, reference.image.width(), reference.image.height(),
                                     options.max_delta_e, "noise dE");
    write_png(dir / "reference-noise.png", noise_image);
    bottom.push_back({std::move(noise_image), fmt::format("reference noise\ndE {:.2f}, p99 {:.2f}", s.mean, s.p99)});
  } else {
    bottom.push_back({Image(), "reference noise\nnot known"});
  }

  std::vector<Result> results;
  for (std::size_t i = 0; i < infos.size(); ++i) {
    const TechniqueInfo* info = infos[i];
    fmt::print(stderr, "technique: {}\n", info->name);
    Result r{render_technique(scene, *info, params[i], options.frames), ImageComparison{}};
    r.metrics = compare_images(r.rendered.image, reference.image);
    write_image_pair(dir, info->name, r.rendered.image);
    Image de = make_delta_e_image(r.rendered.image, reference.image, options.max_delta_e);
    write_png(dir / (info->name + "-de.png"), de);
    write_png(dir / (info->name + "-luminance.png"), make_signed_luminance_image(r.rendered.image, reference.image));
    top.push_back({r.rendered.image, fmt::format("{}\n{:.1f} ms/frame", info->name, r.rendered.timings.frame_ms)});
    bottom.push_back({std::move(de), fmt::format("dE {:.2f}, p99 {:.2f}\nPSNR {:.1f} SSIM {:.3f}", r.metrics.mean_de,
                                                 r.metrics.p99_de, r.metrics.psnr, r.metrics.ssim)});
    results.push_back(std::move(r));
  }
  write_png(dir / "grid.png", make_comparison_grid(interleave_rows(std::move(top), std::move(bottom)), kGridColumns));
  write_reports(dir, options, scene, reference, noise, results);
  for (const Result& r : results) {
    fmt::print("{}: mean dE {:.2f}, p99 dE {:.2f}, PSNR {:.2f} dB, SSIM {:.4f}, {:.1f} ms/frame\n", r.rendered.name,
               r.metrics.mean_de, r.metrics.p99_de, r.metrics.psnr, r.metrics.ssim, r.rendered.timings.frame_ms);
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

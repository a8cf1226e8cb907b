#include "penumbra/techniques/comparison.h"

#include "penumbra/analysis/color_difference.h"
#include "penumbra/base/error.h"
#include "penumbra/render/change_timing.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>

namespace penumbra {

TechniqueRun run_technique(const Scene& scene, const TechniqueInfo& info, const ParameterValues& params, int frames,
                           RenderProgress* progress) {
  TechniqueRun r{info.name, params, Image{}, TechniqueTimings{}, std::nullopt};
  auto technique = info.create();
  technique->set_progress(progress);
  // The first prepare builds the technique's structures; that cost is
  // tf_change_ms / light_move_ms, not part of a frame of an unchanged scene.
  technique->prepare(scene, params);
  std::vector<double> frame_ms;
  for (int f = 0; f < frames; ++f) {
    Image image;
    RenderStats stats;
    const auto t0 = Clock::now();
    technique->prepare(scene, params);
    technique->render(scene, image, &stats);
    frame_ms.push_back(elapsed_ms(t0));
    r.timings.device = stats.device;
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

// The channels of a path share its geometry and differ only by albedo and
// light colour, so their errors are nearly perfectly correlated; moving them
// one at a time would invent chroma noise.
std::vector<float> noise_delta_e(const Image& mean, const Image& standard_error) {
  check_same_size(mean, standard_error);
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

Comparison compare_techniques(const Scene& scene, const ComparisonRequest& request,
                              const ComparisonObserver& on_start, RenderProgress* progress) {
  if (request.frames < 1) throw InvalidArgument("frames", "must be at least 1");
  if (request.techniques.empty()) throw InvalidArgument("techniques", "name at least one technique");
  if (request.params.size() != request.techniques.size()) {
    throw InvalidArgument("params", "give one parameter set per technique");
  }
  const int width = scene.render().width, height = scene.render().height;
  if (!request.reference) {
    if (request.reference_image.width() != width || request.reference_image.height() != height) {
      throw InvalidArgument("reference_image",
                            fmt::format("the reference image is {}x{} but the scene renders {}x{}",
                                        request.reference_image.width(), request.reference_image.height(), width,
                                        height));
    }
  }
  Comparison out;
  if (request.reference) {
    if (on_start) on_start(request.reference->name, true);
    out.reference = run_technique(scene, *request.reference, request.reference_params, 1, progress);
  } else {
    out.reference.name = "reference";
    out.reference.image = request.reference_image;
    out.reference_rendered = false;
  }
  if (out.reference.estimate) {
    out.noise_de = noise_delta_e(out.reference.image, out.reference.estimate->standard_error);
    out.noise = delta_e_stats(out.noise_de);
  }
  for (std::size_t i = 0; i < request.techniques.size(); ++i) {
    if (on_start) on_start(request.techniques[i]->name, false);
    ComparedTechnique c{run_technique(scene, *request.techniques[i], request.params[i], request.frames, progress),
                        ImageComparison{}};
    c.metrics = compare_images(c.run.image, out.reference.image);
    out.techniques.push_back(std::move(c));
  }
  return out;
}

namespace {

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

}  // namespace

std::string comparison_report_json(const Comparison& comparison, const std::string& scene_name,
                                   const std::string& reference_name, int width, int height) {
  const TechniqueRun& reference = comparison.reference;
  std::string json = "{\n";
  json += fmt::format("  \"scene\": {},\n  \"image\": [{}, {}],\n", json_string(scene_name), width, height);
  json += fmt::format("  \"reference\": {{\"source\": {}", json_string(reference_name));
  if (comparison.reference_rendered) {
    json += fmt::format(", \"technique\": {}, \"params\": {}, \"frame_ms\": {}", json_string(reference.name),
                        json_parameters(reference.params), json_number(reference.timings.frame_ms));
  }
  if (reference.estimate) json += fmt::format(", \"paths\": {}", reference.estimate->paths);
  if (const auto& noise = comparison.noise) {
    json += fmt::format(", \"noise_de_mean\": {}, \"noise_de_median\": {}, \"noise_de_p99\": {}, \"noise_de_max\": {}",
                        json_number(noise->mean), json_number(noise->median), json_number(noise->p99),
                        json_number(noise->max));
  }
  json += "},\n  \"techniques\": [\n";
  const auto& results = comparison.techniques;
  for (std::size_t i = 0; i < results.size(); ++i) {
    const ComparedTechnique& r = results[i];
    const TechniqueTimings& t = r.run.timings;
    json += fmt::format(
        "    {{\"technique\": {}, \"params\": {}, \"rmse\": {}, \"psnr\": {}, \"ssim\": {}, \"mean_de\": {}, "
        "\"p99_de\": {}, \"max_de\": {}, \"tf_change_ms\": {}, \"light_move_ms\": {}, \"frame_ms\": {}, "
        "\"aux_bytes\": {}, \"device\": \"{}\"}}{}\n",
        json_string(r.run.name), json_parameters(r.run.params), json_number(r.metrics.rmse),
        json_number(r.metrics.psnr), json_number(r.metrics.ssim), json_number(r.metrics.mean_de),
        json_number(r.metrics.p99_de), json_number(r.metrics.max_de), json_number(t.tf_change_ms),
        json_number(t.light_move_ms), json_number(t.frame_ms), t.aux_bytes, to_string(t.device), i + 1 < results.size() ? "," : "");
  }
  json += "  ]\n}\n";
  return json;
}

}  // namespace penumbra

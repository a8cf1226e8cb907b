#pragma once
// Rendering one scene with several techniques and measuring each against a
// reference (docs/comparison-report.md): what `penumbra compare` writes to
// files and the Python bindings' compare() returns. A technique's images,
// metrics and timings, and report.json's text, are made here once.
//
// Timings as `penumbra bench` takes them: tf_change_ms and light_move_ms are
// medians of 3 prepares after a TF nudge / a 2-degree light move, frame_ms
// the median of `frames` prepare + render of the unchanged scene (after one
// untimed prepare that builds the technique's structures).
#include "penumbra/analysis/image_metrics.h"
#include "penumbra/render/technique.h"
#include "penumbra/techniques/pathtrace/pathtrace.h"

#include "penumbra/backends/device.h"

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace penumbra {

struct TechniqueTimings {
  double tf_change_ms = 0.0;
  double light_move_ms = 0.0;
  double frame_ms = 0.0;
  std::uint64_t aux_bytes = 0;
  Device device = Device::Cpu;  // where its frames rendered
};

struct TechniqueRun {
  std::string name;
  ParameterValues params;
  Image image;  // the first timed frame's
  TechniqueTimings timings;
  std::optional<PathTraceEstimate> estimate;  // when the technique is pathtrace
};

// Renders `scene` with a new instance of the technique and times it. Every
// render reports to `progress` and stops (RenderCancelled) when it asks.
TechniqueRun run_technique(const Scene& scene, const TechniqueInfo& info, const ParameterValues& params, int frames,
                           RenderProgress* progress = nullptr);

// The pathtrace reference's noise in CIEDE2000 per pixel: the colour
// difference one standard error makes, all channels moved together (the
// larger of + and -).
std::vector<float> noise_delta_e(const Image& mean, const Image& standard_error);

struct ComparisonRequest {
  std::vector<const TechniqueInfo*> techniques;
  std::vector<ParameterValues> params;  // one per technique
  // The reference: a technique to render, or a stored image of the scene's size.
  const TechniqueInfo* reference = nullptr;
  ParameterValues reference_params;
  Image reference_image;
  int frames = 3;  // timed frames per technique
};

struct ComparedTechnique {
  TechniqueRun run;
  ImageComparison metrics;
};

struct Comparison {
  TechniqueRun reference;         // named "reference" when it was a stored image
  bool reference_rendered = true; // false for a stored image (no params, no timings)
  std::vector<float> noise_de;    // per pixel, for a pathtrace reference (else empty)
  std::optional<DeltaEStats> noise;
  std::vector<ComparedTechnique> techniques;
};

// Throws InvalidArgument for no techniques, frames < 1, a parameter list of
// another length, or a stored reference whose size is not the scene's.
// `on_start` is told each technique's name before it renders (the reference
// first, with `reference` true).
using ComparisonObserver = std::function<void(const std::string& name, bool reference)>;
Comparison compare_techniques(const Scene& scene, const ComparisonRequest& request,
                              const ComparisonObserver& on_start = {},
                              RenderProgress* progress = nullptr);

// report.json (docs/comparison-report.md). `scene_name` and `reference_name`
// are what the report calls the scene and the reference's source.
std::string comparison_report_json(const Comparison& comparison, const std::string& scene_name,
                                   const std::string& reference_name, int width, int height);

}  // namespace penumbra

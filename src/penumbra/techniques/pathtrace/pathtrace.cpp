#include "penumbra/techniques/pathtrace/pathtrace.h"

#include "penumbra/backends/device.h"
#include "penumbra/base/error.h"
#include "penumbra/base/memory_budget.h"
#include "penumbra/base/parallel.h"
#include "penumbra/render/scene_resources.h"
#include "penumbra/techniques/pathtrace/path_pixels.h"
#include "penumbra/techniques/pathtrace/progress_bar.h"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <vector>

namespace penumbra {

double lightness_standard_error(double mean_luminance, double luminance_standard_error) {
  const double y = std::clamp(mean_luminance, 0.0, 1.0);
  constexpr double kLinearBelow = 216.0 / 24389.0;  // CIE: L* is linear below this Y
  const double slope = y > kLinearBelow ? (116.0 / 3.0) * std::pow(y, -2.0 / 3.0) : 24389.0 / 27.0;
  return slope * luminance_standard_error;
}

namespace {

dvec3 mean_of(const PixelAccumulator& p) { return p.paths ? p.sum / double(p.paths) : dvec3(0.0); }

// Unbiased sample variance of the mean: (sum x^2 - (sum x)^2 / n) / (n (n - 1)).
double variance_of_mean(const PixelAccumulator& p, double sum_x, double sum_x2) {
  if (p.paths < 2) return std::numeric_limits<double>::infinity();
  const double n = double(p.paths);
  return std::max(0.0, sum_x2 - sum_x * sum_x / n) / (n * (n - 1.0));
}

dvec3 standard_error_of(const PixelAccumulator& p) {
  return dvec3(std::sqrt(variance_of_mean(p, p.sum.x, p.sum_squares.x)),
               std::sqrt(variance_of_mean(p, p.sum.y, p.sum_squares.y)),
               std::sqrt(variance_of_mean(p, p.sum.z, p.sum_squares.z)));
}

double lightness_error_of(const PixelAccumulator& p) {
  const double y = luminance(vec3(p.sum));
  const double n = std::max(1.0, double(p.paths));
  return lightness_standard_error(y / n, std::sqrt(variance_of_mean(p, y, p.luminance_squares)));
}

bool same_versions(const SceneVersions& a, const SceneVersions& b) {
  return a.data == b.data && a.transfer_function == b.transfer_function && a.lights == b.lights &&
         a.camera == b.camera && a.material == b.material && a.geometry == b.geometry && a.render == b.render &&
         a.meshes == b.meshes;
}

// Delta and ratio tracking take on average majorant x distance tentative
// collisions to cross a macrocell, so a medium dense enough makes a path
// cost millions of lookups (and at 1e30 the steps vanish below float
// precision: the walk never ends). Refused beyond this many across the
// volume's diagonal: such a medium is opaque at a thousandth of a voxel, and
// every other technique shows it the same at a density 1000 times lower.
constexpr double kMaxCollisionsAcross = 1e6;

void check_tracking_cost(const Scene& scene, const float* majorants, std::size_t cells, const std::string& section) {
  const float densest = cells == 0 ? 0.0f : *std::max_element(majorants, majorants + cells);
  const Box3 box = scene.volume().world_box();
  const double across = double(densest) * double(glm::length(box.upper - box.lower));
  if (!(across <= kMaxCollisionsAcross)) {  // NaN too
    const double density = section == "transfer_function" ? scene.transfer_function().density_scale()
                                                          : scene.shadow_tf().density_scale();
    throw InvalidScene(section + ".density_scale",
                       fmt::format("pathtrace: density_scale {} makes the medium so dense that a path would take "
                                   "about {:.3g} tentative collisions to cross the volume (at most {:.0g}); use a "
                                   "density_scale of at most {:.3g}",
                                   density, across, kMaxCollisionsAcross, density * kMaxCollisionsAcross / across));
  }
}

// The same bound for each mesh's medium, over its world bounds' diagonal.
void check_mesh_tracking_cost(const MeshesView& meshes, const std::vector<Box3>& bounds) {
  for (int m = 0; m < meshes.count; ++m) {
    const Box3& b = bounds[std::size_t(m)];
    const double across = double(meshes.objects[m].sigma_max) * double(glm::length(b.upper - b.lower));
    if (!(across <= kMaxCollisionsAcross)) {
      throw InvalidScene(fmt::format("meshes[{}].material.transfer_function", m),
                         fmt::format("pathtrace: the mesh's medium is so dense that a path would take about {:.3g} "
                                     "tentative collisions to cross it (at most {:.0g}); lower its opacities",
                                     across, kMaxCollisionsAcross));
    }
  }
}

class PathTrace final : public Technique {
 public:
  void prepare(const Scene& scene, const ParameterValues& params) override {
    resources_.update(scene);
    meshes_.update(scene);
    meshes_.build_shapes();
    std::vector<Box3> bounds;
    for (const TriangleMesh& m : meshes_.world_meshes()) bounds.push_back(m.bounds());
    check_mesh_tracking_cost(meshes_.view(), bounds);
    // The shadow TF's majorants share the macrocell grid (and its cell count).
    const std::size_t cells = resources_.majorants().majorant.size();
    check_tracking_cost(scene, resources_.majorants().majorant.data(), cells, "transfer_function");
    if (scene.shadow_transfer_function()) {
      check_tracking_cost(scene, resources_.shadow_view(scene).majorants, cells, "shadow_transfer_function");
    }
    settings_.mode = params.choice("mode") == "single" ? ScatteringMode::Single : ScatteringMode::Multiple;
    settings_.max_bounces = params.integer("max_bounces");
    spp_ = params.integer("spp");
    min_spp_ = params.integer("min_spp");
    target_error_ = params.number("target_error");
    seed_ = std::uint32_t(params.integer("seed"));
    antialias_ = params.flag("antialias");
    progress_ = params.flag("progress");
    progressive_ = params.flag("progressive");
    max_total_spp_ = params.integer("max_total_spp");
    // Progressive renders continue the estimate only while everything this
    // prepare() sees is the same: every part of the scene (the version
    // counters are unique across scenes, so another scene never matches)
    // and every parameter.
    if (!accumulating_ || !same_versions(scene.versions(), estimate_versions_) || !(params == estimate_params_)) {
      accumulating_ = false;
      estimate_versions_ = scene.versions();
      estimate_params_ = params;
    }
  }

  void render(const Scene& scene, Image& image, RenderStats* stats) override {
    const RenderView view = resources_.view(scene);
    const RenderView shadows = resources_.shadow_view(scene);
    const int width = view.width;
    const int height = view.height;
    const std::uint64_t pixels = std::uint64_t(width) * std::uint64_t(height);
    check_memory_budget("pathtrace accumulation buffers",
                        checked_product({pixels, sizeof(PixelAccumulator) + sizeof(vec4)}));
    // Progressive: this render adds spp paths per pixel to the estimate of
    // the previous ones (same state, see prepare()) up to max_total_spp;
    // otherwise it starts again. Sample s of a pixel uses stream s either
    // way, so k renders of spp paths equal one render of k * spp.
    const bool resume = progressive_ && accumulating_ && accumulators_.size() == pixels;
    if (!resume) {
      accumulators_.assign(pixels, PixelAccumulator{});
      estimate_ = PathTraceEstimate{};
      taken_ = 0;
    }
    // Until this render ends well (a cancel or an error leaves a partial
    // pass in the sums), the next one starts again.
    accumulating_ = false;
    const int start = taken_;
    const int goal = progressive_ ? int(std::min<std::int64_t>(std::int64_t(start) + spp_, max_total_spp_)) : spp_;

    ProgressBar bar("pathtrace", progress_);
    RenderProgress* watcher = progress();
    const double budget = double(pixels) * double(std::max(1, goal - start));
    std::atomic<std::uint64_t> lookups{0};
    std::atomic<std::uint64_t> paths{0};
    std::uint64_t skipped = 0;  // paths that pixels stopped early will not take
    const auto add_paths = [&](std::uint64_t taken_now) {
      const std::uint64_t done = paths.fetch_add(taken_now, std::memory_order_relaxed) + taken_now;
      bar.update((double(done) + double(skipped)) / budget);
      if (watcher) watcher->report((double(done) + double(skipped)) / budget);
    };
    const MeshesView meshes = meshes_.view();
    const bool on_device = active_device() == Device::Cuda;
    // One pass: paths [taken, target) of every pixel not done, on the device
    // or over the CPU's tiles, through the same trace_pixel_paths.
    const auto run_pass = [&](const PathPass& pass) {
      if (on_device) {
#if defined(PENUMBRA_HAVE_CUDA)
        const auto active = std::uint64_t(
            std::count_if(accumulators_.begin(), accumulators_.end(), [](const auto& p) { return !p.done; }));
        lookups += trace_paths_device(view, shadows, meshes, settings_, pass, accumulators_);
        add_paths(active * std::uint64_t(pass.target - pass.taken));
#endif
        return;
      }
      with_sampler(view.volume, [&](const auto& sampler) {
        const PathKernel<std::decay_t<decltype(sampler)>> kernel{&view, &shadows, sampler, settings_, meshes};
        parallel_for_tiles(width, height, 16, [&](int x0, int y0, int x1, int y1) {
          if (watcher && watcher->stop_requested()) return;  // the tiles left are skipped
          std::uint64_t tile_lookups = 0;
          std::uint64_t tile_paths = 0;
          for (int y = y0; y < y1; ++y) {
            for (int x = x0; x < x1; ++x) {
              PixelAccumulator& pixel = accumulators_[std::size_t(y) * std::size_t(width) + std::size_t(x)];
              if (pixel.done) continue;
              tile_lookups += trace_pixel_paths(kernel, pass, pixel, x, y);
              tile_paths += std::uint64_t(pass.target - pass.taken);
            }
          }
          lookups.fetch_add(tile_lookups, std::memory_order_relaxed);
          add_paths(tile_paths);
        });
        return 0;
      });
    };
    // Passes of min_spp, then doubling sample counts, the same boundaries
    // whether the estimate grows in one render or over several.
    const auto all_done = [&] {
      return std::all_of(accumulators_.begin(), accumulators_.end(), [](const auto& p) { return p.done; });
    };
    int taken = start;  // paths every active pixel has taken
    while (taken < goal && !estimate_.converged) {
      const int target = taken == 0 ? std::min(goal, min_spp_) : std::min(goal, 2 * taken);
      run_pass(PathPass{width, height, taken, target, seed_, antialias_});
      if (watcher && watcher->stop_requested()) throw RenderCancelled();
      taken = target;
      taken_ = taken;
      ++estimate_.passes;
      if (target_error_ > 0.0 && taken >= min_spp_ && taken < (progressive_ ? max_total_spp_ : spp_)) {
        const std::uint64_t stopped = stop_converged_pixels(width, height);
        skipped += stopped * std::uint64_t(goal - taken);
        if (all_done()) estimate_.converged = true;
      }
    }
    estimate_.spp = taken_;
    estimate_.renders += 1;
    if (taken_ >= (progressive_ ? max_total_spp_ : spp_)) estimate_.converged = true;

    if (image.width() != width || image.height() != height) image = Image(width, height);
    estimate_.standard_error = Image(width, height);
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) {
        const PixelAccumulator& pixel = accumulators_[std::size_t(y) * std::size_t(width) + std::size_t(x)];
        const float n = float(std::max(1u, pixel.paths));
        image.at(x, y) = vec4(vec3(mean_of(pixel)), float(pixel.hits) / n);
        estimate_.standard_error.at(x, y) = vec4(vec3(standard_error_of(pixel)), float(pixel.paths));
      }
    }
    estimate_.paths += paths.load();
    accumulating_ = progressive_;
    if (stats) {
      stats->samples += lookups.load();
      stats->rays += paths.load();
      stats->device = on_device ? Device::Cuda : Device::Cpu;
    }
  }

  // Marks the pixels whose lightness error, and that of their 8 neighbours,
  // is below the target; returns how many it marked. The neighbours guard
  // against false convergence: a pixel whose few paths happened to agree
  // (all of them blocked at the edge of a shadow, say) reports no variance,
  // but its neighbours across the edge do.
  std::uint64_t stop_converged_pixels(int width, int height) {
    std::vector<double> error(accumulators_.size());
    for (std::size_t i = 0; i < error.size(); ++i) error[i] = lightness_error_of(accumulators_[i]);
    std::uint64_t stopped = 0;
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) {
        PixelAccumulator& pixel = accumulators_[std::size_t(y) * std::size_t(width) + std::size_t(x)];
        if (pixel.done) continue;
        double worst = 0.0;
        for (int ny = std::max(0, y - 1); ny <= std::min(height - 1, y + 1); ++ny) {
          for (int nx = std::max(0, x - 1); nx <= std::min(width - 1, x + 1); ++nx) {
            worst = std::max(worst, error[std::size_t(ny) * std::size_t(width) + std::size_t(nx)]);
          }
        }
        if (worst <= target_error_) {
          pixel.done = true;
          ++stopped;
        }
      }
    }
    return stopped;
  }

  std::uint64_t aux_bytes() const override {
    return accumulators_.size() * sizeof(PixelAccumulator) + estimate_.standard_error.pixel_count() * sizeof(vec4) +
           meshes_.bytes();
  }

  const PathTraceEstimate* estimate() const { return estimate_.standard_error.empty() ? nullptr : &estimate_; }

 private:
  SceneResources resources_;
  MeshMedia meshes_;  // the scene's meshes as media (mesh_tracking.h)
  PathSettings settings_;
  int spp_ = 1;
  int min_spp_ = 1;
  double target_error_ = 0.0;
  std::uint32_t seed_ = 0;
  bool antialias_ = false;
  bool progress_ = true;
  bool progressive_ = false;
  int max_total_spp_ = 1;
  // The progressive estimate: paths every active pixel has taken, whether
  // the next render may continue it, and the state it belongs to.
  int taken_ = 0;
  bool accumulating_ = false;
  SceneVersions estimate_versions_;
  ParameterValues estimate_params_;
  std::vector<PixelAccumulator> accumulators_;
  PathTraceEstimate estimate_;
};

}  // namespace

const PathTraceEstimate* pathtrace_estimate(const Technique& technique) {
  const auto* p = dynamic_cast<const PathTrace*>(&technique);
  return p ? p->estimate() : nullptr;
}

TechniqueInfo pathtrace_info() {
  return TechniqueInfo{
      "pathtrace",
      "Monte Carlo reference: delta/ratio tracking path tracing with next-event estimation, single or multiple "
      "scattering",
      ParameterTable{{
          ParameterSpec::choice("mode", "single", {"single", "multiple"},
                                "single: one scattering event lit by transmittance (converges to shadow-rays); "
                                "multiple: full multiple scattering"),
          ParameterSpec::integer("spp", 64, 1, 1 << 20, "paths per pixel (the most a pixel takes)"),
          ParameterSpec::real("target_error", 0.0, 0.0, 100.0,
                              "stop a pixel once the standard error of its lightness (and its 8 neighbours') is "
                              "below this many CIE L* units (0 = always take spp)"),
          ParameterSpec::integer("min_spp", 32, 2, 1 << 20, "paths every pixel takes before target_error may stop it"),
          ParameterSpec::integer("max_bounces", 64, 1, 100000,
                                 "most scattering events per path in multiple mode (Russian roulette from 3 on)"),
          ParameterSpec::integer("seed", 0, 0, 2147483647, "random seed; images are reproducible for a given seed"),
          ParameterSpec::flag("antialias", false,
                              "random positions inside each pixel instead of its centre (which every other "
                              "technique samples)"),
          ParameterSpec::flag("progress", true, "progress bar on stderr while rendering, when stderr is a terminal"),
          ParameterSpec::flag("progressive", false,
                              "each render of an unchanged scene and parameters adds spp paths per pixel to the "
                              "last render's estimate instead of starting again (the web viewer sets it)"),
          ParameterSpec::integer("max_total_spp", 4096, 1, 1 << 24,
                                 "progressive: the most paths per pixel the estimate grows to; renders beyond it "
                                 "return the estimate unchanged"),
      }},
      [] { return std::make_unique<PathTrace>(); },
      /*draws_meshes=*/true};
}

}  // namespace penumbra

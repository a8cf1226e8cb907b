#pragma once
// The technique interface (DESIGN.md 3). A technique turns a Scene into an
// Image. prepare() brings its light-space structures up to date and rebuilds
// only what depends on the scene parts that changed (the scene's version
// counters tell which); render() then draws a frame. Splitting the two is
// what makes "TF change", "light move" and "frame" separately measurable.
#include "penumbra/render/image.h"
#include "penumbra/render/parameters.h"
#include "penumbra/render/render_loop.h"
#include "penumbra/scene/scene.h"

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

namespace penumbra {

// Shared between a thread that renders and one that watches it (the Python
// bindings' progress callback and Ctrl-C check): the fraction of the frame
// done so far, and a request to stop. Long renders (pathtrace) report and
// stop between tiles, throwing RenderCancelled; the others finish their
// frame, which is short.
class RenderProgress {
 public:
  void report(double fraction) { fraction_.store(fraction, std::memory_order_relaxed); }
  double fraction() const { return fraction_.load(std::memory_order_relaxed); }
  void request_stop() { stop_.store(true, std::memory_order_relaxed); }
  bool stop_requested() const { return stop_.load(std::memory_order_relaxed); }

 private:
  std::atomic<double> fraction_{0.0};
  std::atomic<bool> stop_{false};
};

class Technique {
 public:
  virtual ~Technique() = default;

  // Brings every structure the technique needs up to date with the scene and
  // the parameters. Cheap when nothing it depends on changed.
  virtual void prepare(const Scene& scene, const ParameterValues& params) = 0;

  // Renders the scene as last prepared into `image` (resized to the scene's
  // render size). Adds sample counts to `stats` when given.
  virtual void render(const Scene& scene, Image& image, RenderStats* stats = nullptr) = 0;

  // Memory of the technique's own structures (light-space tables, caches),
  // not counting the volume and the shared macrocell grid.
  virtual std::uint64_t aux_bytes() const = 0;

  // How many times prepare() has (re)built the technique's own structures;
  // tests use it to check that only the changes a structure depends on
  // trigger a rebuild.
  virtual std::uint64_t rebuilds() const { return 0; }

  // Where render() reports progress and looks for a request to stop;
  // nullptr (the default) for neither. It must outlive the render calls.
  void set_progress(RenderProgress* progress) { progress_ = progress; }
  RenderProgress* progress() const { return progress_; }

 private:
  RenderProgress* progress_ = nullptr;
};

struct TechniqueInfo {
  std::string name;
  std::string summary;  // one line: what it computes and from which paper
  ParameterTable parameters;
  std::function<std::unique_ptr<Technique>()> create;
  bool draws_meshes = false;  // whether it draws the scene's meshes (scene/mesh.h)
  // Whether its frames render on the CUDA device when CUDA is active (the
  // registry sets it; backends/device.h). The others render on the CPU and
  // say so once on stderr.
  bool has_cuda_path = false;
};

}  // namespace penumbra

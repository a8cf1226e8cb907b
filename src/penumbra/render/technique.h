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

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

namespace penumbra {

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
};

struct TechniqueInfo {
  std::string name;
  std::string summary;  // one line: what it computes and from which paper
  ParameterTable parameters;
  std::function<std::unique_ptr<Technique>()> create;
  bool draws_meshes = false;  // whether it draws the scene's meshes (scene/mesh.h)
};

}  // namespace penumbra

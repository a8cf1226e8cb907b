// The compiled half of penumbra.Renderer, techniques() and compare(): a
// technique instance that keeps its structures between renders of a scene
// that changes only where update() changes it, timed as `penumbra bench`
// times it.
#include "bindings.h"
#include "scene_handle.h"

#include "penumbra/base/error.h"
#include "penumbra/base/memory_budget.h"
#include "penumbra/base/parallel.h"
#include "penumbra/io/image_io.h"
#include "penumbra/io/scene_json.h"
#include "penumbra/render/change_timing.h"
#include "penumbra/techniques/comparison.h"
#include "penumbra/techniques/registry.h"

#include <fmt/format.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <atomic>
#include <optional>

namespace penumbra::python {
namespace {

struct RendererStats {
  double build_ms = 0.0;  // the first prepare, which builds every structure
  double prepare_ms = 0.0;
  double render_ms = 0.0;
  double frame_ms = 0.0;  // prepare + render of the last render()
  std::optional<double> tf_change_ms;   // the last prepare after a TF-only change
  std::optional<double> light_move_ms;  // the last prepare after a lights-only change
  RenderStats last;
  std::uint64_t renders = 0;
};

ParameterSettings settings_from(const py::dict& params) {
  ParameterSettings out;
  for (const auto& [key, value] : params) {
    const std::string name = py::str(key).cast<std::string>();
    out[name] = parameter_value(value, name);
  }
  return out;
}

class RendererHandle {
 public:
  RendererHandle(const SceneHandle& scene, const std::string& technique, const py::dict& params)
      : scene_(scene), info_(&find_technique(technique.empty() ? scene.scene().render().technique : technique)),
        technique_(info_->create()), overrides_(settings_from(params)) {
    params_ = resolve_parameters(scene_.scene(), *info_, overrides_);  // bad parameters fail here, not at render()
  }

  const TechniqueInfo& info() const { return *info_; }
  const SceneHandle& scene() const { return scene_; }
  const ParameterValues& params() const { return params_; }

  std::vector<std::string> update(const py::handle& sections, const std::shared_ptr<const Volume>& volume,
                                  const py::dict& params) {
    const Busy busy(*this);
    ParameterSettings overrides = overrides_;
    for (const auto& [key, value] : params) {
      const std::string name = py::str(key).cast<std::string>();
      if (value.is_none()) overrides.erase(name);  // back to the scene's value or the default
      else overrides[name] = parameter_value(value, name);
    }
    // Checked before anything changes, so a bad update leaves the renderer as it was.
    SceneHandle next = scene_;
    std::vector<std::string> changed = next.update(to_json(sections, "(root)"), volume);
    ParameterValues values = resolve_parameters(next.scene(), *info_, overrides);
    scene_ = std::move(next);
    overrides_ = std::move(overrides);
    if (!(values == params_)) changed.emplace_back("params");
    params_ = std::move(values);
    pending_.insert(pending_.end(), changed.begin(), changed.end());
    return changed;
  }

  std::vector<std::string> orbit(float azimuth_deg, float elevation_deg) {
    const Busy busy(*this);
    std::vector<std::string> changed = scene_.orbit(azimuth_deg, elevation_deg);
    pending_.insert(pending_.end(), changed.begin(), changed.end());
    return changed;
  }

  void prepare() {
    const Busy busy(*this);
    py::gil_scoped_release release;
    prepare_timed();
  }

  Image render(const py::object& callback) {
    const Busy busy(*this);
    RenderProgress progress;
    Image image;
    technique_->set_progress(&progress);
    try {
      run_interruptible(progress, callback, [&] {
        const auto t0 = Clock::now();
        prepare_timed();
        if (progress.stop_requested()) throw RenderCancelled();
        const auto t1 = Clock::now();
        RenderStats stats;
        technique_->render(scene_.scene(), image, &stats);
        stats_.render_ms = elapsed_ms(t1);
        stats_.frame_ms = elapsed_ms(t0);
        stats_.last = stats;
        ++stats_.renders;
      });
    } catch (...) {
      technique_->set_progress(nullptr);
      throw;
    }
    technique_->set_progress(nullptr);
    return image;
  }

  py::object standard_error() const {
    const PathTraceEstimate* e = pathtrace_estimate(*technique_);
    if (!e) return py::none();
    return image_to_array(e->standard_error);
  }

  py::dict stats() const {
    py::dict d;
    d["technique"] = info_->name;
    d["build_ms"] = stats_.build_ms;
    d["prepare_ms"] = stats_.prepare_ms;
    d["render_ms"] = stats_.render_ms;
    d["frame_ms"] = stats_.frame_ms;
    d["tf_change_ms"] = stats_.tf_change_ms ? py::object(py::float_(*stats_.tf_change_ms)) : py::object(py::none());
    d["light_move_ms"] = stats_.light_move_ms ? py::object(py::float_(*stats_.light_move_ms)) : py::object(py::none());
    d["aux_bytes"] = technique_->aux_bytes();
    d["rebuilds"] = technique_->rebuilds();
    d["samples"] = stats_.last.samples;
    d["rays"] = stats_.last.rays;
    d["passes"] = stats_.last.passes;
    d["renders"] = stats_.renders;
    d["threads"] = thread_count();
    return d;
  }

 private:
  // One call at a time: render() lets go of the GIL, and another Python
  // thread must not change the scene under it.
  struct Busy {
    explicit Busy(RendererHandle& r) : renderer(r) {
      if (renderer.busy_.exchange(true)) {
        throw std::runtime_error("this Renderer is busy in another thread; give each thread its own Renderer");
      }
    }
    ~Busy() { renderer.busy_ = false; }
    RendererHandle& renderer;
  };

  // prepare() timed and filed under what changed since the last one.
  void prepare_timed() {
    const auto t0 = Clock::now();
    technique_->prepare(scene_.scene(), params_);
    const double ms = elapsed_ms(t0);
    stats_.prepare_ms = ms;
    std::sort(pending_.begin(), pending_.end());
    pending_.erase(std::unique(pending_.begin(), pending_.end()), pending_.end());
    if (first_prepare_) stats_.build_ms = ms;
    else if (pending_ == std::vector<std::string>{"transfer_function"}) stats_.tf_change_ms = ms;
    else if (pending_ == std::vector<std::string>{"lights"}) stats_.light_move_ms = ms;
    first_prepare_ = false;
    pending_.clear();
  }

  SceneHandle scene_;
  const TechniqueInfo* info_;
  std::unique_ptr<Technique> technique_;
  ParameterSettings overrides_;  // parameters given to the renderer (over the scene's render.params)
  ParameterValues params_;
  RendererStats stats_;
  std::vector<std::string> pending_;  // what changed since the last prepare
  bool first_prepare_ = true;
  std::atomic<bool> busy_{false};
};

py::dict comparison_to_python(const Comparison& c, const std::string& scene_name, int width, int height) {
  const std::string reference_name = c.reference_rendered ? c.reference.name : "reference image";
  py::dict out = from_json(nlohmann::json::parse(comparison_report_json(c, scene_name, reference_name, width, height)));
  py::dict images, delta_e;
  images["reference"] = image_to_array(c.reference.image);
  for (const ComparedTechnique& t : c.techniques) {
    images[py::str(t.run.name)] = image_to_array(t.run.image);
    const std::vector<float> de = delta_e_2000_per_pixel(t.run.image, c.reference.image);
    delta_e[py::str(t.run.name)] = py::array_t<float>({py::ssize_t(height), py::ssize_t(width)}, de.data());
  }
  out["images"] = images;
  out["delta_e"] = delta_e;
  out["reference_noise_de"] =
      c.noise_de.empty() ? py::object(py::none())
                         : py::object(py::array_t<float>({py::ssize_t(height), py::ssize_t(width)}, c.noise_de.data()));
  if (c.reference.estimate) out["reference_standard_error"] = image_to_array(c.reference.estimate->standard_error);
  return out;
}

// compare(): parameters as a dict of technique name -> {name: value} (that
// technique only, strictly) and name -> value (every technique declaring it;
// an error when none does).
py::dict compare(const SceneHandle& scene, const std::vector<std::string>& names, const std::string& reference,
                 const py::object& reference_image, const py::dict& params, int frames, const py::object& callback) {
  ComparisonRequest request;
  request.frames = frames;
  for (const std::string& name : names) request.techniques.push_back(&find_technique(name));
  if (reference_image.is_none()) request.reference = &find_technique(reference);
  else request.reference_image = image_from_array(reference_image, "reference_image");
  std::vector<const TechniqueInfo*> involved = request.techniques;
  if (request.reference) involved.push_back(request.reference);
  ParameterSettings flat;
  std::map<std::string, ParameterSettings> per_technique;
  for (const auto& [key, value] : params) {
    const std::string name = py::str(key).cast<std::string>();
    if (py::isinstance<py::dict>(value)) {
      if (std::none_of(involved.begin(), involved.end(), [&](const TechniqueInfo* i) { return i->name == name; })) {
        throw InvalidArgument("params", fmt::format("'{}' is not among the techniques compared", name));
      }
      per_technique[name] = settings_from(value.cast<py::dict>());
    } else {
      if (std::none_of(involved.begin(), involved.end(), [&](const TechniqueInfo* i) { return i->parameters.find(name); })) {
        throw InvalidArgument(name, "no technique compared declares this parameter (see penumbra.techniques())");
      }
      flat[name] = parameter_value(value, name);
    }
  }
  auto params_for = [&](const TechniqueInfo& info) {
    ParameterSettings settings;
    for (const auto& [name, value] : flat) {
      if (info.parameters.find(name)) settings[name] = value;
    }
    for (const auto& [name, value] : per_technique[info.name]) settings[name] = value;
    return resolve_parameters(scene.scene(), info, settings);
  };
  for (const TechniqueInfo* info : request.techniques) request.params.push_back(params_for(*info));
  if (request.reference) request.reference_params = params_for(*request.reference);

  RenderProgress progress;
  Comparison result;
  run_interruptible(progress, callback, [&] { result = compare_techniques(scene.scene(), request, {}, &progress); });
  const Scene& s = scene.scene();
  const VolumeSource& source = s.volume_source();
  const std::string name = !source.file.empty() ? source.file : !source.builtin.empty() ? source.builtin : "in-memory volume";
  return comparison_to_python(result, name, s.render().width, s.render().height);
}

py::object default_to_python(const ParameterSpec& spec) { return parameter_to_python(spec.default_value, spec.type); }

}  // namespace

void bind_renderer(py::module_& m) {
  py::class_<ParameterSpec>(m, "ParameterSpec", "One technique parameter: name, type, default, range and doc.")
      .def_readonly("name", &ParameterSpec::name)
      .def_property_readonly("type", &ParameterSpec::type_name, "'float', 'int', 'bool' or 'choice'")
      .def_property_readonly("default", &default_to_python)
      .def_property_readonly(
          "range",
          [](const ParameterSpec& p) -> py::object {
            if (p.type == ParameterType::Float) return py::make_tuple(p.min, p.max);
            if (p.type == ParameterType::Int) return py::make_tuple(int(p.min), int(p.max));
            if (p.type == ParameterType::Choice) return py::tuple(py::cast(p.choices));
            return py::make_tuple(false, true);
          },
          "(min, max) for numbers (inclusive), the choices for a choice, (False, True) for a bool")
      .def_readonly("doc", &ParameterSpec::doc)
      .def("__repr__", [](const ParameterSpec& p) {
        return fmt::format("<ParameterSpec {} ({}, default {})>", p.name, p.type_name(), to_string(p.default_value));
      });
  py::class_<TechniqueInfo>(m, "TechniqueInfo", "A technique: its name, one-line summary and parameter table.")
      .def_readonly("name", &TechniqueInfo::name)
      .def_readonly("summary", &TechniqueInfo::summary)
      .def_readonly("draws_meshes", &TechniqueInfo::draws_meshes)
      .def_property_readonly("parameters", [](const TechniqueInfo& t) { return t.parameters.specs(); })
      .def("__repr__", [](const TechniqueInfo& t) {
        return fmt::format("<TechniqueInfo {}: {} parameters>", t.name, t.parameters.specs().size());
      });
  m.def(
      "techniques", [] { return &technique_registry(); }, py::return_value_policy::reference,
      "Every technique, in the order `penumbra techniques` lists them.");
  m.def("technique", &find_technique, py::arg("name"), py::return_value_policy::reference,
        "The technique called name; ParameterError listing the known names otherwise.");

  py::class_<RendererHandle>(m, "RendererHandle")
      .def(py::init<const SceneHandle&, const std::string&, const py::dict&>(), py::arg("scene"),
           py::arg("technique"), py::arg("params"))
      .def_property_readonly("technique", [](const RendererHandle& r) { return r.info().name; })
      .def_property_readonly("scene", [](const RendererHandle& r) { return SceneHandle(r.scene()); })
      .def_property_readonly("params",
                             [](const RendererHandle& r) {
                               py::dict d;
                               for (const ParameterSpec& spec : r.params().table().specs()) {
                                 d[py::str(spec.name)] = parameter_to_python(r.params().value(spec.name), spec.type);
                               }
                               return d;
                             })
      .def(
          "update",
          [](RendererHandle& r, const py::handle& sections, const std::shared_ptr<Volume>& volume,
             const py::dict& params) { return r.update(sections, volume, params); },
          py::arg("sections"), py::arg("volume") = nullptr, py::arg("params") = py::dict())
      .def("orbit", &RendererHandle::orbit, py::arg("azimuth_deg"), py::arg("elevation_deg"))
      .def("prepare", &RendererHandle::prepare)
      .def(
          "render", [](RendererHandle& r, const py::object& callback) { return image_to_array(r.render(callback)); },
          py::arg("progress") = py::none())
      .def(
          "render_srgb",
          [](RendererHandle& r, const py::object& callback) {
            const Image image = r.render(callback);
            const std::vector<std::uint8_t> rgb = srgb8_pixels(image);
            return py::array_t<std::uint8_t>({py::ssize_t(image.height()), py::ssize_t(image.width()), py::ssize_t(3)},
                                             rgb.data());
          },
          py::arg("progress") = py::none())
      .def("standard_error", &RendererHandle::standard_error)
      .def_property_readonly("stats", &RendererHandle::stats);

  m.def("compare", &compare, py::arg("scene"), py::arg("techniques"), py::arg("reference"),
        py::arg("reference_image"), py::arg("params"), py::arg("frames"), py::arg("progress"));

  m.def("set_threads", &set_thread_count, py::arg("threads"),
        "Worker threads of every later render, as the CLI's --threads (0 = all cores).");
  m.def("thread_count", &thread_count, "The worker threads renders use.");
  m.def("memory_budget", &memory_budget_bytes, "Bytes penumbra may allocate for one volume or structure.");
  m.def("set_memory_budget", &set_memory_budget_bytes, py::arg("bytes"),
        "Change the memory budget (default: half of physical memory, or $PENUMBRA_MEMORY_BUDGET_MB).");
}

}  // namespace penumbra::python

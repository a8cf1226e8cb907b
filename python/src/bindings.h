#pragma once
// Shared pieces of the Python bindings (module _penumbra): conversions between
// Python objects and the engine's types, and running long C++ work with the
// GIL released while Ctrl-C and a progress callback stay live.
#include "penumbra/render/image.h"
#include "penumbra/render/parameters.h"
#include "penumbra/render/technique.h"

#include <nlohmann/json.hpp>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <functional>
#include <string>

namespace penumbra::python {

namespace py = pybind11;

// Each part of the module registers its classes and functions.
void bind_errors(py::module_& m);
void bind_volume(py::module_& m);
void bind_scene(py::module_& m);
void bind_renderer(py::module_& m);
void bind_analysis(py::module_& m);

// Python data (dicts, lists, numbers, numpy arrays and scalars) as JSON, and
// back; through Python's json module so every JSON type maps as it does there.
nlohmann::json to_json(const py::handle& object, const std::string& what);
py::object from_json(const nlohmann::json& json);

// An (H, W, 3) or (H, W, 4) array of linear values as an Image (copied; alpha
// 1 when absent). Throws ValueError naming `what` for other shapes and types.
Image image_from_array(const py::handle& array, const std::string& what);
// The image as an (H, W, 4) float32 array that owns its pixels (no copy).
py::array image_to_array(Image image);

// A technique parameter's Python value (bool, number, str) checked against
// nothing yet: ParameterValues::set checks it against the table.
ParameterValue parameter_value(const py::handle& value, const std::string& name);
py::object parameter_to_python(const ParameterValue& value, ParameterType type);

// The technique parameters for `info` as a render of `scene` resolves them
// (the scene's render.params, strictly when the technique is the scene's own;
// then `overrides`, strictly). The pathtrace progress bar on stderr is off
// unless asked for: Python has the progress callback.
ParameterValues resolve_parameters(const Scene& scene, const TechniqueInfo& info, const ParameterSettings& overrides);

// Runs `work` on a worker thread with the GIL released. Every 100 ms the
// calling thread takes the GIL, checks for Ctrl-C (KeyboardInterrupt) and
// calls `callback(fraction)` when `progress` moved; an exception from either
// asks the work to stop (RenderCancelled) and is raised once it has. The
// callback also sees 1.0 when the work is done.
void run_interruptible(RenderProgress& progress, const py::object& callback, const std::function<void()>& work);

}  // namespace penumbra::python

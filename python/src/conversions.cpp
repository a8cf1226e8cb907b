#include "bindings.h"

#include "penumbra/base/error.h"

#include <fmt/format.h>

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <thread>

namespace penumbra::python {

nlohmann::json to_json(const py::handle& object, const std::string& what) {
  const py::module_ json = py::module_::import("json");
  // numpy arrays and scalars (a camera eye from np.array) become lists and numbers.
  const py::cpp_function as_list([](py::handle o) -> py::object {
    if (py::hasattr(o, "tolist")) return o.attr("tolist")();
    throw py::type_error(fmt::format("{} is not JSON data", py::repr(o).cast<std::string>()));
  });
  std::string text;
  try {
    text = json.attr("dumps")(object, py::arg("default") = as_list, py::arg("allow_nan") = false).cast<std::string>();
  } catch (py::error_already_set& e) {
    if (!e.matches(PyExc_ValueError) && !e.matches(PyExc_TypeError)) throw;
    throw InvalidScene(what, e.what());
  }
  return nlohmann::json::parse(text);
}

py::object from_json(const nlohmann::json& json) {
  return py::module_::import("json").attr("loads")(json.dump());
}

Image image_from_array(const py::handle& object, const std::string& what) {
  const py::module_ np = py::module_::import("numpy");
  py::array given = py::array::ensure(object);
  if (!given) throw InvalidArgument(what, "expected an (H, W, 3) or (H, W, 4) array");
  const char kind = given.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u') {
    throw InvalidArgument(what, fmt::format("expected linear float values, got dtype {}",
                                            py::str(given.dtype()).cast<std::string>()));
  }
  if (given.ndim() != 3 || (given.shape(2) != 3 && given.shape(2) != 4)) {
    throw InvalidArgument(what, fmt::format("expected an (H, W, 3) or (H, W, 4) array, got shape {}",
                                            py::str(given.attr("shape")).cast<std::string>()));
  }
  const auto pixels = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(given);
  const int height = int(pixels.shape(0)), width = int(pixels.shape(1)), channels = int(pixels.shape(2));
  Image image(width, height, vec4(0.0f, 0.0f, 0.0f, 1.0f));
  const float* in = pixels.data();
  for (std::size_t i = 0; i < image.pixel_count(); ++i) {
    for (int c = 0; c < channels; ++c) image.data()[i][c] = in[i * std::size_t(channels) + std::size_t(c)];
  }
  return image;
}

py::array image_to_array(Image image) {
  auto* owned = new Image(std::move(image));
  py::capsule owner(owned, [](void* p) { delete static_cast<Image*>(p); });
  const py::ssize_t h = owned->height(), w = owned->width();
  return py::array_t<float>({h, w, py::ssize_t(4)},
                            {py::ssize_t(sizeof(float)) * 4 * w, py::ssize_t(sizeof(float)) * 4,
                             py::ssize_t(sizeof(float))},
                            reinterpret_cast<const float*>(owned->data()), owner);
}

ParameterValue parameter_value(const py::handle& value, const std::string& name) {
  if (py::isinstance<py::bool_>(value) || py::isinstance(value, py::module_::import("numpy").attr("bool_"))) {
    return py::reinterpret_borrow<py::object>(value).attr("__bool__")().cast<bool>();
  }
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  const py::module_ numbers = py::module_::import("numbers");
  if (py::isinstance(value, numbers.attr("Real"))) return py::reinterpret_steal<py::float_>(PyNumber_Float(value.ptr())).cast<double>();
  throw InvalidArgument(name, fmt::format("expected a number, bool or string, got {}",
                                          py::repr(value).cast<std::string>()));
}

py::object parameter_to_python(const ParameterValue& value, ParameterType type) {
  if (const double* d = std::get_if<double>(&value)) {
    if (type == ParameterType::Int) return py::int_(static_cast<long long>(*d));
    return py::float_(*d);
  }
  if (const bool* b = std::get_if<bool>(&value)) return py::bool_(*b);
  return py::str(std::get<std::string>(value));
}

ParameterValues resolve_parameters(const Scene& scene, const TechniqueInfo& info, const ParameterSettings& overrides) {
  ParameterValues values(info.parameters);
  try {
    values.apply(scene.render().params, scene.render().technique == info.name);
  } catch (const InvalidArgument& e) {
    throw InvalidScene("render.params." + e.name(), e.what());
  }
  const bool progress_asked = overrides.contains("progress") || scene.render().params.contains("progress");
  if (info.parameters.find("progress") && !progress_asked) values.set("progress", false);
  for (const auto& [name, value] : overrides) values.set(name, value);
  return values;
}

void run_interruptible(RenderProgress& progress, const py::object& callback, const std::function<void()>& work) {
  std::exception_ptr failure;
  std::optional<py::error_already_set> python_error;
  std::mutex mutex;
  std::condition_variable finished;
  bool done = false;
  double reported = -1.0;
  // Holds the GIL: Ctrl-C and the callback, whose error stops the work.
  auto watch = [&] {
    if (python_error) return;
    try {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      const double fraction = progress.fraction();
      if (!callback.is_none() && fraction != reported) {
        reported = fraction;
        callback(fraction);
      }
    } catch (py::error_already_set& e) {
      python_error.emplace(std::move(e));
      progress.request_stop();
    }
  };
  {
    py::gil_scoped_release release;
    std::thread worker([&] {
      try {
        work();
      } catch (...) {
        failure = std::current_exception();
      }
      std::lock_guard lock(mutex);
      done = true;
      finished.notify_all();
    });
    std::unique_lock lock(mutex);
    while (!finished.wait_for(lock, std::chrono::milliseconds(100), [&] { return done; })) {
      lock.unlock();
      {
        py::gil_scoped_acquire acquire;
        watch();
      }
      lock.lock();
    }
    lock.unlock();
    worker.join();
  }
  if (python_error) throw *python_error;  // the work's RenderCancelled is its echo
  if (failure) std::rethrow_exception(failure);
  progress.report(1.0);
  watch();
  if (python_error) throw *python_error;
}

}  // namespace penumbra::python

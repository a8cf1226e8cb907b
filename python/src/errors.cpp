// penumbra's C++ exceptions as Python exceptions, with the C++ message:
//   IoError           -> penumbra.FileError, an OSError (filename set)
//   InvalidScene      -> penumbra.SceneError, a ValueError (key set)
//   InvalidArgument   -> penumbra.ParameterError, a ValueError (name set)
//   OutOfMemoryBudget -> penumbra.MemoryBudgetError, a MemoryError (bytes set)
//   RenderCancelled   -> KeyboardInterrupt
//   any other Error   -> RuntimeError
#include "bindings.h"

#include "penumbra/base/error.h"

namespace penumbra::python {
namespace {

// Raises an instance of `type` made from `message`, with one attribute set.
void raise_with(PyObject* type, const char* message, const char* attribute, const py::object& value) {
  py::object error = py::reinterpret_steal<py::object>(PyObject_CallFunction(type, "s", message));
  if (!error) return;  // the call itself raised; that error stands
  error.attr(attribute) = value;
  PyErr_SetObject(type, error.ptr());
}

}  // namespace

void bind_errors(py::module_& m) {
  static py::exception<InvalidScene> scene_error(m, "SceneError", PyExc_ValueError);
  static py::exception<InvalidArgument> parameter_error(m, "ParameterError", PyExc_ValueError);
  static py::exception<OutOfMemoryBudget> budget_error(m, "MemoryBudgetError", PyExc_MemoryError);
  static py::exception<IoError> file_error(m, "FileError", PyExc_OSError);
  // The C++ message as it is: OSError's own str() would print "[Errno None]"
  // once filename is set.
  file_error.attr("__str__") = py::module_::import("builtins").attr("BaseException").attr("__str__");
  file_error.doc() = "A file that cannot be read or written, or whose content is malformed; .filename names it.";
  scene_error.doc() = "A scene with a missing, unknown or ill-typed key; .key is its path, e.g. 'lights[1].direction'.";
  parameter_error.doc() = "A bad technique parameter or argument; .name names it.";
  budget_error.doc() = "An allocation over penumbra's memory budget; .bytes is what it needed.";
  for (py::handle type : {scene_error.ptr(), parameter_error.ptr(), budget_error.ptr(), file_error.ptr()}) {
    type.attr("__module__") = "penumbra";  // as users import them
  }
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const IoError& e) {
      raise_with(file_error.ptr(), e.what(), "filename", py::str(e.path()));
    } catch (const InvalidScene& e) {
      raise_with(scene_error.ptr(), e.what(), "key", py::str(e.key()));
    } catch (const InvalidArgument& e) {
      raise_with(parameter_error.ptr(), e.what(), "name", py::str(e.name()));
    } catch (const OutOfMemoryBudget& e) {
      raise_with(budget_error.ptr(), e.what(), "bytes", py::int_(e.bytes()));
    } catch (const RenderCancelled&) {
      PyErr_SetNone(PyExc_KeyboardInterrupt);
    } catch (const Error& e) {
      PyErr_SetString(PyExc_RuntimeError, e.what());
    }
  });
}

}  // namespace penumbra::python

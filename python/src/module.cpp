// The compiled half of the `penumbra` Python package (python/penumbra wraps
// it). Every function here is a thin layer over the C++ library.
#include "bindings.h"

PYBIND11_MODULE(_penumbra, m) {
  m.doc() = "penumbra's C++ engine (use the penumbra package, which wraps this module)";
  penumbra::python::bind_errors(m);
  penumbra::python::bind_volume(m);
  penumbra::python::bind_scene(m);
  penumbra::python::bind_renderer(m);
  penumbra::python::bind_analysis(m);
}

// The compiled half of penumbra.Scene (python/penumbra/scene.py): a
// SceneHandle made from scene JSON v1 (a dict) or a scene file.
#include "bindings.h"
#include "scene_handle.h"

#include "penumbra/base/error.h"
#include "penumbra/io/binary_file.h"
#include "penumbra/io/scene_json.h"

#include <fmt/format.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

namespace penumbra::python {
namespace {

std::shared_ptr<const Volume> optional_volume(const std::shared_ptr<Volume>& v) { return v; }

SceneHandle from_file(const std::filesystem::path& path) {
  if (!std::filesystem::is_regular_file(path)) throw IoError(path.string(), "cannot open scene file");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(read_text_file(path));
  } catch (const nlohmann::json::parse_error& e) {
    throw IoError(path.string(), fmt::format("not valid JSON: {}", e.what()));
  }
  return SceneHandle(j, std::filesystem::absolute(path).parent_path(), nullptr);
}

py::dict versions_of(const SceneVersions& v) {
  py::dict d;
  d["data"] = v.data;
  d["transfer_function"] = v.transfer_function;
  d["lights"] = v.lights;
  d["camera"] = v.camera;
  d["material"] = v.material;
  d["geometry"] = v.geometry;
  d["render"] = v.render;
  d["meshes"] = v.meshes;
  return d;
}

}  // namespace

void bind_scene(py::module_& m) {
  py::class_<SceneHandle>(m, "SceneHandle")
      .def(py::init([](const py::handle& sections, const std::filesystem::path& base_dir,
                       const std::shared_ptr<Volume>& volume) {
             return SceneHandle(to_json(sections, "(root)"), base_dir, optional_volume(volume));
           }),
           py::arg("sections"), py::arg("base_dir"), py::arg("volume") = nullptr)
      .def_static("from_file", &from_file, py::arg("path"))
      .def("copy", [](const SceneHandle& s) { return SceneHandle(s); })
      .def(
          "update",
          [](SceneHandle& s, const py::handle& sections, const std::shared_ptr<Volume>& volume) {
            return s.update(to_json(sections, "(root)"), optional_volume(volume));
          },
          py::arg("sections"), py::arg("volume") = nullptr)
      .def("orbit", &SceneHandle::orbit, py::arg("azimuth_deg"), py::arg("elevation_deg"))
      .def("to_json", [](const SceneHandle& s) { return from_json(s.to_json()); })
      .def("to_json_text", [](const SceneHandle& s) {
        if (s.memory_volume()) {
          throw InvalidScene("volume", "the scene's volume is in memory; save it (Volume.save) and name the file");
        }
        return write_scene_json(s.scene());
      })
      .def_property_readonly("volume",
                             [](const SceneHandle& s) { return std::const_pointer_cast<Volume>(s.scene().volume_ptr()); })
      .def_property_readonly("volume_in_memory", [](const SceneHandle& s) { return s.memory_volume() != nullptr; })
      .def_property_readonly("base_dir", &SceneHandle::base_dir)
      .def_property_readonly("versions", [](const SceneHandle& s) { return versions_of(s.scene().versions()); });
}

}  // namespace penumbra::python

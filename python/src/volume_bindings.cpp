// penumbra.Volume: a volume from a numpy array without a copy where the
// layout allows (the volume keeps the array alive), read_volume(), to_numpy()
// and save(). Axis order is numpy's C order: array[z, y, x] for one frame,
// array[t, z, y, x] for a time series, so x is fastest as in the files.
#include "bindings.h"

#include "penumbra/base/error.h"
#include "penumbra/io/volume_reader.h"
#include "penumbra/io/volume_writer.h"

#include <fmt/format.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <algorithm>
#include <climits>
#include <optional>

namespace penumbra::python {
namespace {

std::optional<VoxelType> voxel_type_of(const py::dtype& dtype) {
  const char kind = dtype.kind();
  const auto size = dtype.itemsize();
  if (kind == 'u' && size == 1) return VoxelType::UInt8;
  if (kind == 'i' && size == 1) return VoxelType::Int8;
  if (kind == 'u' && size == 2) return VoxelType::UInt16;
  if (kind == 'i' && size == 2) return VoxelType::Int16;
  if (kind == 'u' && size == 4) return VoxelType::UInt32;
  if (kind == 'i' && size == 4) return VoxelType::Int32;
  if (kind == 'f' && size == 4) return VoxelType::Float32;
  if (kind == 'f' && size == 8) return VoxelType::Float64;
  return std::nullopt;
}

py::dtype dtype_of(VoxelType type) {
  return py::dtype(std::string(to_string(type)));  // "uint8", "int16", "float32", ...
}

vec3 to_vec3(const std::vector<double>& v, const char* name) {
  if (v.size() != 3) throw InvalidArgument(name, fmt::format("expected 3 numbers (x, y, z), got {}", v.size()));
  return vec3(float(v[0]), float(v[1]), float(v[2]));
}

// Releases the array with the GIL held, whichever thread drops the volume.
std::shared_ptr<const void> keep_alive(py::array array) {
  return std::shared_ptr<const void>(new py::object(std::move(array)), [](const void* p) {
    if (!Py_IsInitialized()) return;  // the interpreter is gone; so is the array
    py::gil_scoped_acquire acquire;
    delete static_cast<const py::object*>(p);
  });
}

std::shared_ptr<Volume> volume_from_array(const py::object& object, const std::vector<double>& spacing,
                                          const std::optional<std::vector<double>>& origin, const py::object& copy) {
  const py::module_ np = py::module_::import("numpy");
  py::array array = py::array::ensure(object);
  if (!array) throw InvalidArgument("array", "expected a numpy array (or anything numpy.asarray accepts)");
  if (array.ndim() != 3 && array.ndim() != 4) {
    throw InvalidArgument("array", fmt::format("expected a 3D (z, y, x) or 4D (t, z, y, x) array, got shape {}",
                                               py::str(array.attr("shape")).cast<std::string>()));
  }
  const std::optional<VoxelType> type = voxel_type_of(array.dtype());
  if (!type) {
    throw InvalidArgument("array", fmt::format("dtype {} is not a voxel type penumbra stores (uint8, int8, uint16, "
                                               "int16, uint32, int32, float32, float64); convert it with astype()",
                                               py::str(array.dtype()).cast<std::string>()));
  }
  const bool native = array.dtype().attr("isnative").cast<bool>();
  const int flags = py::detail::array_proxy(array.ptr())->flags;
  const bool aligned = (flags & py::detail::npy_api::NPY_ARRAY_ALIGNED_) != 0;
  const bool contiguous = (flags & py::detail::npy_api::NPY_ARRAY_C_CONTIGUOUS_) != 0;
  const bool wrappable = native && aligned && contiguous;
  if (copy.is(py::bool_(false)) && !wrappable) {
    throw InvalidArgument("copy", fmt::format("the array cannot be used without a copy ({}); pass copy=None to allow one",
                                              !contiguous ? "it is not C-contiguous"
                                              : !native   ? "its byte order is not the machine's"
                                                          : "its data is not aligned"));
  }
  if (!wrappable || py::bool_(copy).cast<bool>()) {
    array = np.attr("array")(array, py::arg("dtype") = array.dtype().attr("newbyteorder")("="), py::arg("order") = "C",
                             py::arg("copy") = true);
  }
  std::vector<py::ssize_t> shape(array.shape(), array.shape() + array.ndim());
  for (py::ssize_t n : shape) {
    if (n > INT_MAX) throw InvalidArgument("array", "a dimension is larger than 2^31 - 1");
  }
  const int frames = array.ndim() == 4 ? int(shape[0]) : 1;
  const std::size_t last = shape.size() - 1;
  const ivec3 dims{int(shape[last]), int(shape[last - 1]), int(shape[last - 2])};
  const auto* data = static_cast<const std::byte*>(array.data());
  auto volume = std::make_shared<Volume>(Volume::wrap(dims, *type, frames, data, keep_alive(array)));
  volume->set_spacing(to_vec3(spacing, "spacing"));
  if (origin) volume->set_origin(to_vec3(*origin, "origin"));
  volume->set_source("numpy array");
  return volume;
}

// A read-only view of frames [first, first + count) when they lie one after
// another in memory (always for one frame and for wrapped volumes), else a copy.
py::array frames_to_numpy(const py::object& self, const Volume& volume, int first, int count, bool keep_4d) {
  const ivec3 d = volume.dims();
  std::vector<py::ssize_t> shape{d.z, d.y, d.x};
  if (keep_4d) shape.insert(shape.begin(), count);
  const py::dtype dtype = dtype_of(volume.type());
  const std::byte* start = volume.frame_data(first);
  bool adjacent = true;
  for (int f = first + 1; f < first + count; ++f) {
    adjacent = adjacent && volume.frame_data(f) == start + std::uint64_t(f - first) * volume.frame_bytes();
  }
  py::array out;
  if (adjacent) {
    out = py::array(dtype, shape, {}, start, self);
    out.attr("setflags")(py::arg("write") = false);
  } else {
    out = py::array(dtype, shape);
    auto* dst = static_cast<std::byte*>(out.mutable_data());
    for (int f = 0; f < count; ++f) {
      std::copy_n(volume.frame_data(first + f), volume.frame_bytes(), dst + std::uint64_t(f) * volume.frame_bytes());
    }
  }
  return out;
}

void save_volume(const Volume& volume, const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext == ".nrrd" || ext == ".nhdr") {
    write_nrrd(path, volume);
  } else if (ext == ".mha" || ext == ".mhd") {
    write_metaimage(path, volume);
  } else if (ext == ".vti") {
    if (volume.frame_count() > 1) throw InvalidArgument("path", "a .vti file holds one frame; use .nrrd for a series");
    write_vti(path, volume);
  } else if (path.string().ends_with(".nii.gz") || ext == ".nii") {
    throw InvalidArgument("path", "penumbra reads NIfTI but does not write it; use .nrrd, .mha or .vti");
  } else {
    throw InvalidArgument("path", fmt::format("'{}': save as .nrrd, .nhdr, .mha, .mhd or .vti", path.string()));
  }
}

}  // namespace

void bind_volume(py::module_& m) {
  py::class_<Volume, std::shared_ptr<Volume>>(m, "Volume", R"doc(
A grid of scalars with spacing, origin and one or more time steps (frames).

Volume(array, spacing=(1, 1, 1), origin=None, copy=None)

array is indexed [z, y, x] (numpy's C order, x fastest, as volume files store
voxels), or [t, z, y, x] for a time series. Voxel types: uint8, int8, uint16,
int16, uint32, int32, float32, float64. A C-contiguous, aligned array in the
machine's byte order is used in place: the volume keeps the array alive and
reads its memory, so no voxel is copied. Otherwise it is copied, unless
copy=False, which raises ValueError instead; copy=True always copies.
spacing is (x, y, z) in world units; origin is the world position of voxel
(0, 0, 0), by default such that the box is centred at the world origin.
If you write into a shared array later, call modified() and give the volume
to the scene or renderer again (update(volume=...)).
)doc")
      .def(py::init(&volume_from_array), py::arg("array"), py::arg("spacing") = std::vector<double>{1.0, 1.0, 1.0},
           py::arg("origin") = py::none(), py::arg("copy") = py::none())
      .def_property_readonly("dims", [](const Volume& v) { return py::make_tuple(v.dims().x, v.dims().y, v.dims().z); },
                             "(x, y, z) voxel counts")
      .def_property_readonly(
          "shape",
          [](const Volume& v) {
            const ivec3 d = v.dims();
            return v.frame_count() > 1 ? py::make_tuple(v.frame_count(), d.z, d.y, d.x) : py::make_tuple(d.z, d.y, d.x);
          },
          "the numpy shape of to_numpy(): (z, y, x), or (t, z, y, x) for a series")
      .def_property_readonly("frames", &Volume::frame_count, "number of time steps")
      .def_property_readonly("dtype", [](const Volume& v) { return dtype_of(v.type()); })
      .def_property_readonly("spacing", [](const Volume& v) { return py::make_tuple(v.spacing().x, v.spacing().y, v.spacing().z); })
      .def_property_readonly("origin", [](const Volume& v) { return py::make_tuple(v.origin().x, v.origin().y, v.origin().z); })
      .def_property_readonly(
          "bounds",
          [](const Volume& v) {
            const Box3 b = v.world_box();
            return py::make_tuple(py::make_tuple(b.lower.x, b.lower.y, b.lower.z),
                                  py::make_tuple(b.upper.x, b.upper.y, b.upper.z));
          },
          "((xmin, ymin, zmin), (xmax, ymax, zmax)): the box of the voxel centres in world units")
      .def_property_readonly("nbytes", &Volume::total_bytes)
      .def_property_readonly("source", &Volume::source, "where the volume came from (a path, a generator, 'numpy array')")
      .def_property_readonly("shares_memory", &Volume::wraps_external_memory,
                             "whether the voxels are an array's memory (no copy was made)")
      .def(
          "value_range",
          [](const Volume& v, std::optional<int> frame) {
            const ValueRange r = frame ? v.value_range(*frame) : v.value_range();
            return py::make_tuple(r.min, r.max);
          },
          py::arg("frame") = py::none(), "(min, max) of the finite voxels of one frame or of all frames")
      .def("modified", &Volume::mark_modified,
           "Forget cached value ranges after the shared array was written (see the class doc).")
      .def(
          "to_numpy",
          [](py::object self, std::optional<int> frame) {
            const Volume& v = self.cast<const Volume&>();
            if (frame) return frames_to_numpy(self, v, *frame, 1, false);
            return frames_to_numpy(self, v, 0, v.frame_count(), v.frame_count() > 1);
          },
          py::arg("frame") = py::none(),
          "The voxels as a read-only array [z, y, x] (or [t, z, y, x] for a series; one frame with frame=). No copy is "
          "made, except for a series read from a file, whose frames lie apart.")
      .def(
          "__array__",
          [](py::object self, py::object dtype, py::object) {
            const Volume& v = self.cast<const Volume&>();
            py::array a = frames_to_numpy(self, v, 0, v.frame_count(), v.frame_count() > 1);
            return dtype.is_none() ? py::object(a) : a.attr("astype")(dtype);
          },
          py::arg("dtype") = py::none(), py::arg("copy") = py::none())
      .def("save", [](const Volume& v, const std::filesystem::path& path) { save_volume(v, path); }, py::arg("path"),
           "Write the volume as .nrrd/.nhdr (a series as 4D), .mha/.mhd or .vti (one frame).")
      .def("__repr__", [](const Volume& v) {
        const ivec3 d = v.dims();
        return fmt::format("<penumbra.Volume {}x{}x{} {}{}, spacing ({}, {}, {}), {}>", d.x, d.y, d.z,
                           to_string(v.type()), v.frame_count() > 1 ? fmt::format(", {} frames", v.frame_count()) : "",
                           v.spacing().x, v.spacing().y, v.spacing().z, v.source());
      });

  m.def(
      "read_volume", [](const std::filesystem::path& path) { return read_volume(path); }, py::arg("path"),
      "Read a volume file: .nrrd .nhdr (raw/gzip, 4D series), .mha .mhd, .nii .nii.gz, .vti, .dat (+ .raw).\n"
      "Raises OSError for a missing or malformed file.");
  m.def("supported_volume_extensions", &supported_volume_extensions);
}

}  // namespace penumbra::python

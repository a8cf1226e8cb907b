// Image metrics on arrays (analysis/image_metrics.h) and image files.
#include "bindings.h"

#include "penumbra/analysis/image_metrics.h"
#include "penumbra/base/error.h"
#include "penumbra/io/image_io.h"

#include <fmt/format.h>
#include <pybind11/stl/filesystem.h>

#include <algorithm>

namespace penumbra::python {
namespace {

// Both arrays as images: test first, reference second, as the metrics take them.
std::pair<Image, Image> pair_of(const py::handle& test, const py::handle& reference) {
  return {image_from_array(test, "test"), image_from_array(reference, "reference")};
}

template <class Metric> auto metric(Metric f) {
  return [f](const py::handle& test, const py::handle& reference) {
    const auto [a, b] = pair_of(test, reference);
    return f(a, b);
  };
}

std::string extension_of(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

}  // namespace

void bind_analysis(py::module_& m) {
  const char* pair_doc = "(test, reference): (H, W, 3) or (H, W, 4) linear float arrays of one size; alpha is ignored.";
  m.def("rmse", metric([](const Image& a, const Image& b) { return rmse(a, b); }), py::arg("test"),
        py::arg("reference"), (std::string("RMSE over linear R, G, B. ") + pair_doc).c_str());
  m.def("psnr", metric([](const Image& a, const Image& b) { return psnr(a, b); }), py::arg("test"),
        py::arg("reference"), (std::string("PSNR in dB with peak 1.0 (inf for identical images). ") + pair_doc).c_str());
  m.def("ssim", metric([](const Image& a, const Image& b) { return ssim(a, b); }), py::arg("test"),
        py::arg("reference"),
        (std::string("Mean SSIM (Wang et al. 2004) of the sRGB-encoded luma, 11x11 Gaussian window. ") + pair_doc).c_str());
  m.def(
      "delta_e_2000",
      [](const py::handle& test, const py::handle& reference) {
        const auto [a, b] = pair_of(test, reference);
        const std::vector<float> de = delta_e_2000_per_pixel(a, b);
        return py::array_t<float>({py::ssize_t(a.height()), py::ssize_t(a.width())}, de.data());
      },
      py::arg("test"), py::arg("reference"),
      (std::string("Per-pixel CIEDE2000 as an (H, W) float32 array (colours clamped to [0, 1]). ") + pair_doc).c_str());
  m.def(
      "compare_images",
      [](const py::handle& test, const py::handle& reference) {
        const auto [a, b] = pair_of(test, reference);
        const ImageComparison c = compare_images(a, b);
        py::dict d;
        d["rmse"] = c.rmse;
        d["psnr"] = c.psnr;
        d["ssim"] = c.ssim;
        d["mean_de"] = c.mean_de;
        d["median_de"] = c.median_de;
        d["p99_de"] = c.p99_de;
        d["max_de"] = c.max_de;
        d["mae"] = c.mae;
        return d;
      },
      py::arg("test"), py::arg("reference"),
      (std::string("Every metric at once: rmse, psnr, ssim, mean/median/p99/max CIEDE2000, mae. ") + pair_doc).c_str());

  m.def(
      "encode_png",
      [](const py::handle& image) {
        const std::vector<std::uint8_t> png = encode_png(image_from_array(image, "image"));
        return py::bytes(reinterpret_cast<const char*>(png.data()), png.size());
      },
      py::arg("image"), "The PNG file `penumbra render -o x.png` writes for this linear image, as bytes.");
  m.def(
      "srgb8",
      [](const py::handle& image) {
        const Image i = image_from_array(image, "image");
        const std::vector<std::uint8_t> rgb = srgb8_pixels(i);
        return py::array_t<std::uint8_t>({py::ssize_t(i.height()), py::ssize_t(i.width()), py::ssize_t(3)}, rgb.data());
      },
      py::arg("image"), "The 8-bit sRGB (H, W, 3) pixels a PNG of this linear image holds.");
  m.def(
      "read_image",
      [](const std::filesystem::path& path) {
        const std::string ext = extension_of(path);
        if (ext == ".exr") return image_to_array(read_exr(path));
        if (ext == ".png") return image_to_array(read_png(path));
        throw InvalidArgument("path", fmt::format("'{}': read .png or .exr images", path.string()));
      },
      py::arg("path"), "A PNG (decoded to linear) or EXR as an (H, W, 4) float32 array.");
  m.def(
      "write_image",
      [](const std::filesystem::path& path, const py::handle& image) {
        const std::string ext = extension_of(path);
        const Image i = image_from_array(image, "image");
        if (ext == ".exr") write_exr(path, i);
        else if (ext == ".png") write_png(path, i);
        else throw InvalidArgument("path", fmt::format("'{}': the output must end in .png or .exr", path.string()));
      },
      py::arg("path"), py::arg("image"), "Write a linear image as 8-bit sRGB PNG or linear float EXR, as the CLI does.");
}

}  // namespace penumbra::python

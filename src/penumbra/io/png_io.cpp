#include "penumbra/analysis/color_space.h"
#include "penumbra/base/error.h"
#include "penumbra/base/memory_budget.h"
#include "penumbra/io/binary_file.h"
#include "penumbra/io/image_io.h"

#include <fmt/format.h>
#include <png.h>

#include <array>
#include <cmath>
#include <cstring>

namespace penumbra {
namespace {

// libpng's simplified API reports errors through png_image::message instead
// of longjmp, which is what makes it safe to call from C++.
struct PngImage {
  png_image image;
  PngImage() {
    std::memset(&image, 0, sizeof image);
    image.version = PNG_IMAGE_VERSION;
  }
  ~PngImage() { png_image_free(&image); }
};

// 8-bit sRGB code of a linear value: clamp, encode with the exact curve,
// round to nearest in encoded space.
std::uint8_t encode_channel(float linear) {
  if (!(linear > 0.0f)) return 0;  // also NaN
  if (linear >= 1.0f) return 255;
  return static_cast<std::uint8_t>(std::lround(srgb_encode(linear) * 255.0f));
}

std::vector<std::uint8_t> rgb_bytes(const Image& image, const std::string& destination) {
  if (image.empty()) throw IoError(destination, "cannot write an empty (0 x 0) image as PNG");
  return srgb8_pixels(image);
}

void prepare_write(PngImage& png, const Image& image) {
  png.image.width = static_cast<png_uint_32>(image.width());
  png.image.height = static_cast<png_uint_32>(image.height());
  png.image.format = PNG_FORMAT_RGB;
}

Image finish_read(PngImage& png, const std::string& source) {
  png.image.format = PNG_FORMAT_RGBA;
  const std::uint64_t pixels = std::uint64_t(png.image.width) * png.image.height;
  check_memory_budget(fmt::format("decoding {} ({}x{})", source, png.image.width, png.image.height),
                      checked_product({pixels, 4 + sizeof(vec4)}));
  std::vector<std::uint8_t> rgba(PNG_IMAGE_SIZE(png.image));
  if (!png_image_finish_read(&png.image, nullptr, rgba.data(), 0, nullptr)) {
    throw IoError(source, fmt::format("cannot decode PNG: {}", png.image.message));
  }
  std::array<float, 256> linear;
  for (int i = 0; i < 256; ++i) linear[static_cast<std::size_t>(i)] = srgb_decode(float(i) / 255.0f);
  Image image(static_cast<int>(png.image.width), static_cast<int>(png.image.height));
  for (std::size_t i = 0; i < image.pixel_count(); ++i) {
    image.data()[i] = vec4(linear[rgba[4 * i]], linear[rgba[4 * i + 1]], linear[rgba[4 * i + 2]],
                           float(rgba[4 * i + 3]) / 255.0f);
  }
  return image;
}

std::vector<std::uint8_t> encode_png_to(const Image& image, const std::string& destination) {
  const std::vector<std::uint8_t> rgb = rgb_bytes(image, destination);
  PngImage png;
  prepare_write(png, image);
  png_alloc_size_t size = 0;
  if (!png_image_write_to_memory(&png.image, nullptr, &size, 0, rgb.data(), 0, nullptr)) {
    throw IoError(destination, fmt::format("cannot encode PNG: {}", png.image.message));
  }
  std::vector<std::uint8_t> bytes(size);
  if (!png_image_write_to_memory(&png.image, bytes.data(), &size, 0, rgb.data(), 0, nullptr)) {
    throw IoError(destination, fmt::format("cannot encode PNG: {}", png.image.message));
  }
  bytes.resize(size);
  return bytes;
}

}  // namespace

std::vector<std::uint8_t> srgb8_pixels(const Image& image) {
  std::vector<std::uint8_t> rgb(image.pixel_count() * 3);
  for (std::size_t i = 0; i < image.pixel_count(); ++i) {
    const vec4 p = image.data()[i];
    rgb[3 * i + 0] = encode_channel(p.r);
    rgb[3 * i + 1] = encode_channel(p.g);
    rgb[3 * i + 2] = encode_channel(p.b);
  }
  return rgb;
}

std::vector<std::uint8_t> encode_png(const Image& image) { return encode_png_to(image, "<memory>"); }

void write_png(const std::filesystem::path& path, const Image& image) {
  const std::vector<std::uint8_t> bytes = encode_png_to(image, display_path(path));
  write_whole_file(path, std::as_bytes(std::span(bytes)));
}

Image read_png(const std::filesystem::path& path) {
  const std::vector<std::byte> bytes = read_whole_file(path);
  PngImage png;
  if (!png_image_begin_read_from_memory(&png.image, bytes.data(), bytes.size())) {
    throw IoError(display_path(path), fmt::format("not a readable PNG: {}", png.image.message));
  }
  return finish_read(png, display_path(path));
}

Image decode_png(std::span<const std::uint8_t> bytes) {
  PngImage png;
  if (!png_image_begin_read_from_memory(&png.image, bytes.data(), bytes.size())) {
    throw IoError("<memory>", fmt::format("not a readable PNG: {}", png.image.message));
  }
  return finish_read(png, "<memory>");
}

}  // namespace penumbra

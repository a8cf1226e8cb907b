#include "server/image_encoding.h"

#include "penumbra/analysis/color_space.h"
#include "penumbra/base/error.h"
#include "penumbra/io/image_io.h"

#include <fmt/format.h>

// jpeglib.h needs FILE and size_t declared before it.
#include <cstdio>
#include <jpeglib.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <setjmp.h>

namespace penumbra::server {
namespace {

// 8-bit code of every 1/kSteps of linear [0, 1]: a table lookup per channel
// instead of a pow(). Rounding the input to 1/16384 moves the encoded value by
// at most 12.92 * 255 / 32768 = 0.1 code (the curve's steepest slope), so a
// code differs from write_png's only next to a rounding tie, and by one.
constexpr int kSteps = 16384;

const std::array<std::uint8_t, kSteps + 1>& srgb_table() {
  static const auto table = [] {
    std::array<std::uint8_t, kSteps + 1> t{};
    for (int i = 0; i <= kSteps; ++i) t[std::size_t(i)] = std::uint8_t(std::lround(srgb_encode(float(i) / kSteps) * 255.0f));
    return t;
  }();
  return table;
}

std::uint8_t encode_channel(float linear, const std::array<std::uint8_t, kSteps + 1>& table) {
  if (!(linear > 0.0f)) return 0;  // also NaN
  if (linear >= 1.0f) return 255;
  return table[std::size_t(std::lround(linear * kSteps))];
}

struct JpegErrorManager {
  jpeg_error_mgr base;
  jmp_buf jump;
  char message[JMSG_LENGTH_MAX];
};

void on_jpeg_error(j_common_ptr info) {
  auto* manager = reinterpret_cast<JpegErrorManager*>(info->err);
  (*info->err->format_message)(info, manager->message);
  longjmp(manager->jump, 1);
}

}  // namespace

std::optional<ImageFormat> image_format_from_string(std::string_view name) {
  if (name == "jpeg" || name == "jpg") return ImageFormat::Jpeg;
  if (name == "png") return ImageFormat::Png;
  return std::nullopt;
}

std::string_view mime_type(ImageFormat format) { return format == ImageFormat::Jpeg ? "image/jpeg" : "image/png"; }

std::vector<std::uint8_t> to_srgb8(const Image& image) {
  const auto& table = srgb_table();
  std::vector<std::uint8_t> rgb(image.pixel_count() * 3);
  const vec4* pixels = image.data();
  for (std::size_t i = 0; i < image.pixel_count(); ++i) {
    rgb[3 * i + 0] = encode_channel(pixels[i].r, table);
    rgb[3 * i + 1] = encode_channel(pixels[i].g, table);
    rgb[3 * i + 2] = encode_channel(pixels[i].b, table);
  }
  return rgb;
}

std::vector<std::uint8_t> encode_jpeg(const Image& image, int quality) {
  if (quality < 1 || quality > 100) throw InvalidArgument("quality", fmt::format("must be in [1, 100], got {}", quality));
  if (image.empty()) throw InvalidArgument("image", "cannot encode an empty image");
  const std::vector<std::uint8_t> rgb = to_srgb8(image);

  // libjpeg reports errors by longjmp. Everything it may jump over lives on
  // the heap behind a pointer that is set before setjmp and never changed
  // after it, so its state is well defined in the error branch, which
  // releases it and throws from ordinary code.
  struct Compressor {
    jpeg_compress_struct info{};
    JpegErrorManager errors{};
    unsigned char* buffer = nullptr;
    unsigned long size = 0;
  };
  const auto c = std::make_unique<Compressor>();
  c->info.err = jpeg_std_error(&c->errors.base);
  c->errors.base.error_exit = on_jpeg_error;
  if (setjmp(c->errors.jump)) {
    jpeg_destroy_compress(&c->info);
    std::free(c->buffer);
    throw IoError("<jpeg>", fmt::format("cannot encode JPEG: {}", c->errors.message));
  }
  jpeg_create_compress(&c->info);
  jpeg_mem_dest(&c->info, &c->buffer, &c->size);
  c->info.image_width = JDIMENSION(image.width());
  c->info.image_height = JDIMENSION(image.height());
  c->info.input_components = 3;
  c->info.in_color_space = JCS_RGB;
  jpeg_set_defaults(&c->info);
  jpeg_set_quality(&c->info, quality, TRUE);
  if (quality >= 90) {
    for (int i = 0; i < c->info.num_components; ++i) {
      c->info.comp_info[i].h_samp_factor = 1;
      c->info.comp_info[i].v_samp_factor = 1;
    }
  }
  jpeg_start_compress(&c->info, TRUE);
  const std::size_t stride = std::size_t(image.width()) * 3;
  while (c->info.next_scanline < c->info.image_height) {
    JSAMPROW row = const_cast<JSAMPROW>(rgb.data() + c->info.next_scanline * stride);
    jpeg_write_scanlines(&c->info, &row, 1);
  }
  jpeg_finish_compress(&c->info);
  std::vector<std::uint8_t> out(c->buffer, c->buffer + c->size);
  jpeg_destroy_compress(&c->info);
  std::free(c->buffer);
  return out;
}

std::vector<std::uint8_t> encode_image(const Image& image, ImageFormat format, int jpeg_quality) {
  return format == ImageFormat::Jpeg ? encode_jpeg(image, jpeg_quality) : encode_png(image);
}

}  // namespace penumbra::server

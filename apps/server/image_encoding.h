#pragma once
// Frames on the wire: JPEG (libjpeg-turbo) for interaction, PNG (lossless,
// io/image_io.h) for saving. Both carry 8-bit sRGB made from the linear image
// with the same curve and rounding as write_png, so a JPEG differs from the
// PNG of the same frame only by compression.
#include "penumbra/render/image.h"

#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

namespace penumbra::server {

enum class ImageFormat { Jpeg, Png };

// "jpeg"/"jpg" or "png"; nullopt for anything else.
std::optional<ImageFormat> image_format_from_string(std::string_view name);
std::string_view mime_type(ImageFormat format);

// 8-bit sRGB, row 0 at the top, 3 bytes per pixel (alpha dropped, NaN -> 0).
std::vector<std::uint8_t> to_srgb8(const Image& image);

// Baseline JPEG, 4:2:0 below quality 90 and 4:4:4 from 90 up (fine colour
// edges of TF bands survive). Throws InvalidArgument for quality outside
// [1, 100] or an empty image.
std::vector<std::uint8_t> encode_jpeg(const Image& image, int quality);

std::vector<std::uint8_t> encode_image(const Image& image, ImageFormat format, int jpeg_quality);

}  // namespace penumbra::server

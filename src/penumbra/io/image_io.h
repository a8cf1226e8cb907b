#pragma once
// Image files. PNG is for looking at: 8-bit RGB, sRGB-encoded with the exact
// IEC 61966-2-1 curve after clamping to [0, 1] (alpha is dropped; NaN is
// written as 0). EXR is for measuring: linear float32 RGBA, lossless, so a
// rendered image can be read back bit for bit. Errors throw IoError.
#include "penumbra/render/image.h"

#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

namespace penumbra {

void write_png(const std::filesystem::path& path, const Image& image);
// The pixels such a PNG holds: 8-bit sRGB R, G, B per pixel, rows top first.
std::vector<std::uint8_t> srgb8_pixels(const Image& image);
// The same PNG bytes, in memory (for the HTTP server).
std::vector<std::uint8_t> encode_png(const Image& image);
// Decodes sRGB to linear; alpha is 1 unless the file has an alpha channel.
Image read_png(const std::filesystem::path& path);
Image decode_png(std::span<const std::uint8_t> bytes);

void write_exr(const std::filesystem::path& path, const Image& image);
// Channels R, G, B, A (missing colour channels read as 0, missing alpha as 1).
Image read_exr(const std::filesystem::path& path);

}  // namespace penumbra

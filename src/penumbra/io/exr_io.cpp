#include "penumbra/base/error.h"
#include "penumbra/base/memory_budget.h"
#include "penumbra/io/binary_file.h"
#include "penumbra/io/image_io.h"

#include <fmt/format.h>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>

#include <exception>

namespace penumbra {
namespace {

constexpr const char* kChannels[4] = {"R", "G", "B", "A"};

// Points the four channels of a FrameBuffer at an Image's interleaved floats
// covering `window` (Slice::Make does the data-window offset arithmetic).
Imf::FrameBuffer frame_buffer(const float* pixels, const Imath::Box2i& window, const float fill[4]) {
  Imf::FrameBuffer buffer;
  const std::size_t x_stride = sizeof(vec4);
  const std::size_t y_stride = sizeof(vec4) * static_cast<std::size_t>(window.max.x - window.min.x + 1);
  for (int c = 0; c < 4; ++c) {
    buffer.insert(kChannels[c], Imf::Slice::Make(Imf::FLOAT, pixels + c, window, x_stride, y_stride, 1, 1, fill[c]));
  }
  return buffer;
}

}  // namespace

void write_exr(const std::filesystem::path& path, const Image& image) {
  if (image.empty()) throw IoError(display_path(path), "cannot write an empty (0 x 0) image as EXR");
  try {
    Imf::Header header(image.width(), image.height());
    header.compression() = Imf::ZIP_COMPRESSION;
    for (const char* name : kChannels) header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    Imf::OutputFile file(path.c_str(), header);
    const float fill[4] = {0.0f, 0.0f, 0.0f, 1.0f};
    file.setFrameBuffer(frame_buffer(&image.data()->x, header.dataWindow(), fill));
    file.writePixels(image.height());
  } catch (const std::exception& e) {
    throw IoError(display_path(path), fmt::format("cannot write EXR: {}", e.what()));
  }
}

Image read_exr(const std::filesystem::path& path) {
  file_size_checked(path);  // a clear "file not found" before OpenEXR's message
  try {
    Imf::InputFile file(path.c_str());
    const Imath::Box2i window = file.header().dataWindow();
    const std::int64_t width = std::int64_t(window.max.x) - window.min.x + 1;
    const std::int64_t height = std::int64_t(window.max.y) - window.min.y + 1;
    if (width <= 0 || height <= 0 || width > (1 << 30) || height > (1 << 30)) {
      throw IoError(display_path(path), fmt::format("EXR data window {}x{} is empty or absurd", width, height));
    }
    check_memory_budget(fmt::format("reading {} ({}x{})", display_path(path), width, height),
                        checked_product({std::uint64_t(width), std::uint64_t(height), sizeof(vec4)}));
    Image image(static_cast<int>(width), static_cast<int>(height));
    const float fill[4] = {0.0f, 0.0f, 0.0f, 1.0f};
    file.setFrameBuffer(frame_buffer(&image.data()->x, window, fill));
    file.readPixels(window.min.y, window.max.y);
    return image;
  } catch (const IoError&) {
    throw;
  } catch (const std::exception& e) {
    throw IoError(display_path(path), fmt::format("cannot read EXR: {}", e.what()));
  }
}

}  // namespace penumbra

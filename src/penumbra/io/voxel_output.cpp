#include "penumbra/io/voxel_output.h"

#include "penumbra/base/error.h"
#include "penumbra/base/memory_budget.h"
#include "penumbra/io/binary_file.h"
#include "penumbra/io/volume_bytes.h"

namespace penumbra {

OutputFile::OutputFile(const std::filesystem::path& path) : path_(path), out_(path, std::ios::binary | std::ios::trunc) {
  if (!out_) throw IoError(display_path(path), "cannot open the file for writing");
}

void OutputFile::write(std::span<const std::byte> bytes) {
  out_.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (!out_) throw IoError(display_path(path_), "write failed (disk full?)");
}

void OutputFile::write(std::string_view text) {
  write(std::span(reinterpret_cast<const std::byte*>(text.data()), text.size()));
}

void OutputFile::close() {
  out_.flush();
  if (!out_) throw IoError(display_path(path_), "write failed (disk full?)");
  out_.close();
}

namespace {

void stream_voxels(const Volume& volume, int first_frame, int frame_count, std::endian byte_order,
                   std::optional<CompressionFormat> compression, const ByteSink& sink) {
  std::optional<Deflater> deflater;
  if (compression) deflater.emplace(*compression);
  for (int f = first_frame; f < first_frame + frame_count; ++f) {
    for_each_voxel_chunk(volume, f, byte_order, [&](std::span<const std::byte> chunk) {
      if (deflater) {
        deflater->write(chunk, sink);
      } else {
        sink(chunk);
      }
    });
  }
  if (deflater) deflater->finish(sink);
}

}  // namespace

void write_voxels(OutputFile& out, const Volume& volume, int first_frame, int frame_count, std::endian byte_order,
                  std::optional<CompressionFormat> compression) {
  stream_voxels(volume, first_frame, frame_count, byte_order, compression,
                [&](std::span<const std::byte> piece) { out.write(piece); });
}

std::vector<std::byte> voxel_bytes(const Volume& volume, int first_frame, int frame_count, std::endian byte_order,
                                   std::optional<CompressionFormat> compression) {
  std::vector<std::byte> bytes;
  bytes.reserve(static_cast<std::size_t>(compression ? volume.frame_bytes() / 4 : volume.frame_bytes() * frame_count));
  stream_voxels(volume, first_frame, frame_count, byte_order, compression,
                [&](std::span<const std::byte> piece) { bytes.insert(bytes.end(), piece.begin(), piece.end()); });
  return bytes;
}

}  // namespace penumbra

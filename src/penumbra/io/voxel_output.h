#pragma once
// The output side shared by the volume writers: a file opened for writing
// whose failures become IoError, and the voxel bytes of frames streamed into
// it in a given byte order, optionally through a compressor.
#include "penumbra/io/compression.h"
#include "penumbra/volume/volume.h"

#include <bit>
#include <filesystem>
#include <fstream>
#include <optional>
#include <span>
#include <string_view>

namespace penumbra {

class OutputFile {
 public:
  explicit OutputFile(const std::filesystem::path& path);
  void write(std::span<const std::byte> bytes);
  void write(std::string_view text);
  // Flushes and checks; call once at the end (the destructor does not throw).
  void close();

 private:
  std::filesystem::path path_;
  std::ofstream out_;
};

// Voxels of frames [first_frame, first_frame + frame_count) as one stream,
// compressed with `compression` when set.
void write_voxels(OutputFile& out, const Volume& volume, int first_frame, int frame_count, std::endian byte_order,
                  std::optional<CompressionFormat> compression);

// The same stream in memory (the caller checks the size against the memory
// budget first).
std::vector<std::byte> voxel_bytes(const Volume& volume, int first_frame, int frame_count, std::endian byte_order,
                                   std::optional<CompressionFormat> compression);

}  // namespace penumbra

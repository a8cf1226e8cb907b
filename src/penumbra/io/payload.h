#pragma once
// Voxel payloads in files: raw bytes or a zlib/gzip stream at some offset of
// a file. Every reader describes its payload(s) with PayloadSource, checks
// them all with check_payload_size() before allocating the Volume, and then
// streams them into the volume with read_payload().
#include "penumbra/io/volume_bytes.h"

#include <cstdint>
#include <filesystem>
#include <string>

namespace penumbra {

enum class PayloadEncoding { Raw, Compressed };

struct PayloadSource {
  std::filesystem::path file;
  PayloadEncoding encoding = PayloadEncoding::Raw;
  // Where the payload (compressed or not) starts in the file.
  std::uint64_t offset = 0;
  // Raw only: the payload is the last bytes of the file, whatever `offset`
  // says (NRRD "byte skip: -1", MetaImage "HeaderSize = -1").
  bool at_end = false;
  // Compressed only: decompressed bytes to discard before the voxels (NRRD
  // applies "byte skip" after decompression).
  std::uint64_t skip_after_decoding = 0;
  // When the file's length is known to bound the compressed stream exactly
  // (MetaImage CompressedDataSize), 0 = up to the end of the file.
  std::uint64_t compressed_size = 0;
};

// Throws IoError unless the source can hold `bytes` bytes of voxels: a raw
// payload must have them in the file, a compressed one must be big enough to
// expand to them (see max_inflated_size). `what` names the data in messages.
void check_payload_size(const PayloadSource& source, std::uint64_t bytes, const std::string& what);

// Copies `bytes` bytes of voxels from the source into the cursor.
void read_payload(const PayloadSource& source, std::uint64_t bytes, VolumeByteCursor& cursor,
                  const std::string& what);

// Offset just past `lines` newline characters counted from `start`; IoError
// if the file has fewer lines.
std::uint64_t offset_after_lines(const std::filesystem::path& file, std::uint64_t start, std::uint64_t lines);

}  // namespace penumbra

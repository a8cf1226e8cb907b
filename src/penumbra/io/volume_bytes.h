#pragma once
// A Volume's voxels as one byte stream: frame 0, then frame 1, ... in file
// order (x fastest). Readers fill it piece by piece from files, whatever the
// file boundaries (NRRD may split the stream over many files, one per slice
// or per frame); writers drain it in bounded chunks so no second full copy of
// a volume is ever made.
#include "penumbra/volume/volume.h"

#include <bit>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>

namespace penumbra {

class VolumeByteCursor {
 public:
  explicit VolumeByteCursor(Volume& volume) : volume_(volume) {}

  std::uint64_t remaining() const;
  // The next contiguous piece of at most max_bytes (never spanning frames);
  // empty when the volume is full.
  std::span<std::byte> next(std::uint64_t max_bytes);

 private:
  Volume& volume_;
  int frame_ = 0;
  std::uint64_t offset_ = 0;  // within frame_
};

// Converts every frame from `file_order` to host order.
void convert_volume_byte_order(Volume& volume, std::endian file_order);

// Calls sink with the voxel bytes of `frame` in `file_order`, in chunks of at
// most `chunk_bytes`.
void for_each_voxel_chunk(const Volume& volume, int frame, std::endian file_order,
                          const std::function<void(std::span<const std::byte>)>& sink,
                          std::size_t chunk_bytes = std::size_t(1) << 20);

}  // namespace penumbra

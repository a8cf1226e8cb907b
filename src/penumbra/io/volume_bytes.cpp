#include "penumbra/io/volume_bytes.h"

#include "penumbra/io/byte_order.h"

#include <algorithm>
#include <vector>

namespace penumbra {

std::uint64_t VolumeByteCursor::remaining() const {
  if (frame_ >= volume_.frame_count()) return 0;
  return volume_.frame_bytes() * std::uint64_t(volume_.frame_count() - frame_) - offset_;
}

std::span<std::byte> VolumeByteCursor::next(std::uint64_t max_bytes) {
  if (frame_ >= volume_.frame_count() || max_bytes == 0) return {};
  const std::uint64_t n = std::min(max_bytes, volume_.frame_bytes() - offset_);
  std::span<std::byte> piece(volume_.frame_data(frame_) + offset_, static_cast<std::size_t>(n));
  offset_ += n;
  if (offset_ == volume_.frame_bytes()) {
    ++frame_;
    offset_ = 0;
  }
  return piece;
}

void convert_volume_byte_order(Volume& volume, std::endian file_order) {
  if (file_order == std::endian::native || voxel_size(volume.type()) == 1) return;
  for (int f = 0; f < volume.frame_count(); ++f) {
    swap_bytes(std::span(volume.frame_data(f), static_cast<std::size_t>(volume.frame_bytes())),
               voxel_size(volume.type()));
  }
}

void for_each_voxel_chunk(const Volume& volume, int frame, std::endian file_order,
                          const std::function<void(std::span<const std::byte>)>& sink, std::size_t chunk_bytes) {
  const std::size_t element = voxel_size(volume.type());
  chunk_bytes = std::max(element, chunk_bytes / element * element);
  const std::byte* data = volume.frame_data(frame);
  const std::uint64_t total = volume.frame_bytes();
  const bool swap = file_order != std::endian::native && element > 1;
  std::vector<std::byte> scratch(swap ? chunk_bytes : 0);
  for (std::uint64_t offset = 0; offset < total; offset += chunk_bytes) {
    const std::size_t n = static_cast<std::size_t>(std::min<std::uint64_t>(chunk_bytes, total - offset));
    if (!swap) {
      sink(std::span(data + offset, n));
      continue;
    }
    std::copy(data + offset, data + offset + n, scratch.begin());
    swap_bytes(std::span(scratch.data(), n), element);
    sink(std::span<const std::byte>(scratch.data(), n));
  }
}

}  // namespace penumbra

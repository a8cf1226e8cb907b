#pragma once
// Byte order of file payloads. Files record it (NRRD 'endian', MetaImage
// BinaryDataByteOrderMSB, NIfTI by sizeof_hdr, VTK byte_order); voxels are
// swapped once after loading so everything downstream sees host order.
#include <bit>
#include <cstddef>
#include <span>
#include <utility>

namespace penumbra {

static_assert(std::endian::native == std::endian::little || std::endian::native == std::endian::big,
              "mixed-endian hosts are not supported");

// Reverses the bytes of each element_size-byte element in place.
inline void swap_bytes(std::span<std::byte> data, std::size_t element_size) {
  if (element_size <= 1) return;
  const std::size_t count = data.size() / element_size;
  std::byte* p = data.data();
  for (std::size_t i = 0; i < count; ++i, p += element_size) {
    for (std::size_t a = 0, b = element_size - 1; a < b; ++a, --b) std::swap(p[a], p[b]);
  }
}

// Converts elements stored in `order` to host order (or back: the operation
// is its own inverse).
inline void convert_byte_order(std::span<std::byte> data, std::size_t element_size, std::endian order) {
  if (order != std::endian::native) swap_bytes(data, element_size);
}

}  // namespace penumbra

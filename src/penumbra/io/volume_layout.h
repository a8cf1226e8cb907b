#pragma once
// What a volume header says about the voxels, independent of the format, and
// the one routine that turns it plus payload files into a Volume. Keeping the
// order of checks in one place is what guarantees that every reader validates
// sizes against the files and the memory budget before allocating.
#include "penumbra/io/payload.h"
#include "penumbra/volume/volume.h"

#include <bit>
#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

namespace penumbra {

struct VolumeLayout {
  ivec3 dims{0};
  int frame_count = 1;
  VoxelType type = VoxelType::UInt8;
  std::endian byte_order = std::endian::little;
  vec3 spacing{1.0f};
  std::optional<vec3> origin;  // nullopt: keep the Volume's centred default
};

// Bytes of all frames; UINT64_MAX on overflow (which then fails every check).
std::uint64_t layout_bytes(const VolumeLayout& layout);

// Checks that the payloads (which split the voxel stream into equal parts, in
// order) can hold the voxels, allocates the Volume (memory budget), reads the
// payloads, converts to host byte order and sets spacing, origin and source.
// `header` is the file the user opened; it becomes Volume::source.
std::shared_ptr<Volume> load_volume(const std::filesystem::path& header, const VolumeLayout& layout,
                                    const std::vector<PayloadSource>& payloads);

}  // namespace penumbra

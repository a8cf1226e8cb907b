#include "penumbra/io/volume_layout.h"

#include "penumbra/base/error.h"
#include "penumbra/base/memory_budget.h"
#include "penumbra/io/binary_file.h"

#include <fmt/format.h>

namespace penumbra {

std::uint64_t layout_bytes(const VolumeLayout& layout) {
  return checked_product({std::uint64_t(layout.dims.x), std::uint64_t(layout.dims.y), std::uint64_t(layout.dims.z),
                          std::uint64_t(layout.frame_count), voxel_size(layout.type)});
}

std::shared_ptr<Volume> load_volume(const std::filesystem::path& header, const VolumeLayout& layout,
                                    const std::vector<PayloadSource>& payloads) {
  const ivec3 d = layout.dims;
  if (d.x <= 0 || d.y <= 0 || d.z <= 0 || layout.frame_count <= 0) {
    throw IoError(display_path(header), fmt::format("dimensions must be positive, got {}x{}x{} with {} frame(s)",
                                                    d.x, d.y, d.z, layout.frame_count));
  }
  if (!(layout.spacing.x > 0.0f && layout.spacing.y > 0.0f && layout.spacing.z > 0.0f) ||
      !is_finite(layout.spacing.x) || !is_finite(layout.spacing.y) || !is_finite(layout.spacing.z)) {
    throw IoError(display_path(header), fmt::format("voxel spacing must be positive and finite, got {} {} {}",
                                                    layout.spacing.x, layout.spacing.y, layout.spacing.z));
  }
  if (layout.origin) {
    const vec3 o = *layout.origin;
    if (!is_finite(o.x) || !is_finite(o.y) || !is_finite(o.z)) {
      throw IoError(display_path(header), fmt::format("origin must be finite, got {} {} {}", o.x, o.y, o.z));
    }
  }
  if (payloads.empty()) throw IoError(display_path(header), "no voxel data file");
  const std::uint64_t total = layout_bytes(layout);
  const std::string description =
      layout.frame_count > 1
          ? fmt::format("voxel data ({}x{}x{}x{} {})", d.x, d.y, d.z, layout.frame_count, to_string(layout.type))
          : fmt::format("voxel data ({}x{}x{} {})", d.x, d.y, d.z, to_string(layout.type));
  // Budget first: a header claiming 100 GB is a budget problem whatever the
  // files hold, and saying so is clearer than "truncated".
  check_memory_budget(fmt::format("{} from {}", description, display_path(header)), total);
  if (total % payloads.size() != 0) {
    throw IoError(display_path(header), fmt::format("{} bytes of voxels cannot be split evenly over {} data files",
                                                    total, payloads.size()));
  }
  const std::uint64_t per_payload = total / payloads.size();
  for (const PayloadSource& source : payloads) check_payload_size(source, per_payload, description);

  auto volume = std::make_shared<Volume>(layout.dims, layout.type, layout.frame_count);
  VolumeByteCursor cursor(*volume);
  for (const PayloadSource& source : payloads) read_payload(source, per_payload, cursor, description);
  convert_volume_byte_order(*volume, layout.byte_order);

  try {
    volume->set_spacing(layout.spacing);
    if (layout.origin) volume->set_origin(*layout.origin);
  } catch (const InvalidArgument& e) {
    throw IoError(display_path(header), e.what());  // a spacing of 1e38 puts the box at infinity
  }
  volume->set_source(display_path(header));
  return volume;
}

}  // namespace penumbra

#include "server/volume_histogram.h"

#include "penumbra/base/error.h"

#include <fmt/format.h>

#include <cmath>

namespace penumbra::server {

VolumeHistogram volume_histogram(const Volume& volume, int frame, vec2 range, int bins) {
  if (bins < 1 || bins > 4096) throw InvalidArgument("bins", fmt::format("must be in [1, 4096], got {}", bins));
  if (!(range.x < range.y) || !std::isfinite(range.x) || !std::isfinite(range.y)) {
    throw InvalidArgument("range", fmt::format("needs finite min < max, got [{}, {}]", range.x, range.y));
  }
  VolumeHistogram h;
  h.range = range;
  h.counts.assign(std::size_t(bins), 0);
  const std::uint64_t n = volume.voxel_count();
  const double lo = range.x;
  const double scale = double(bins) / (double(range.y) - double(range.x));
  visit_voxel_type(volume.type(), [&](auto zero) {
    using T = decltype(zero);
    const T* voxels = volume.frame_as<T>(frame);
    for (std::uint64_t i = 0; i < n; ++i) {
      const double v = double(voxels[i]);
      if (!std::isfinite(v)) {
        ++h.non_finite;
      } else if (v < range.x) {
        ++h.below;
      } else if (v > range.y) {
        ++h.above;
      } else {
        // The top edge belongs to the last bin.
        const auto bin = std::min(std::int64_t((v - lo) * scale), std::int64_t(bins - 1));
        ++h.counts[std::size_t(bin)];
      }
    }
    return 0;
  });
  return h;
}

}  // namespace penumbra::server

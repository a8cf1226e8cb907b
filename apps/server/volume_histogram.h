#pragma once
// Histogram of one time step of a volume over a value range: the backdrop of
// the viewer's transfer-function editor, binned over the TF's own range so
// that bin i covers the normalised TF values [i / bins, (i + 1) / bins).
#include "penumbra/base/math.h"
#include "penumbra/volume/volume.h"

#include <cstdint>
#include <vector>

namespace penumbra::server {

struct VolumeHistogram {
  vec2 range{0.0f, 1.0f};
  std::vector<std::uint64_t> counts;
  std::uint64_t below = 0;       // finite voxels under range.x
  std::uint64_t above = 0;       // finite voxels over range.y
  std::uint64_t non_finite = 0;  // NaN and inf voxels
};

// Throws InvalidArgument for bins outside [1, 4096] or an empty range.
VolumeHistogram volume_histogram(const Volume& volume, int frame, vec2 range, int bins);

}  // namespace penumbra::server

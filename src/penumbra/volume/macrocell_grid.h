#pragma once
// Macrocell min/max grid: the value range of every block of cell_size^3 voxel
// cells. Combined with a transfer function's maximum extinction over a value
// range it tells the marching loop which blocks are empty (empty-space
// skipping) and gives the path tracer a piecewise-constant majorant.
//
// Macrocell c covers the index-space box [c * cell_size, (c + 1) * cell_size]
// (clamped to the grid), and its range includes every voxel a trilinear sample
// inside that box can touch, so the bound is conservative.
#include "penumbra/base/math.h"
#include "penumbra/volume/volume_view.h"

#include <cstdint>
#include <vector>

namespace penumbra {

struct MacrocellView {
  const vec2* min_max = nullptr;  // per macrocell (min, max), x fastest
  ivec3 dims{0};                  // macrocells per axis
  int cell_size = 8;              // voxel cells per macrocell edge

  PENUMBRA_HD std::int64_t index(ivec3 c) const {
    return c.x + std::int64_t(dims.x) * (c.y + std::int64_t(dims.y) * c.z);
  }
};

class MacrocellGrid {
 public:
  static constexpr int kDefaultCellSize = 8;

  MacrocellGrid() = default;
  explicit MacrocellGrid(const VolumeView& volume, int cell_size = kDefaultCellSize);

  ivec3 dims() const { return dims_; }
  int cell_size() const { return cell_size_; }
  vec2 min_max(ivec3 cell) const { return min_max_[static_cast<std::size_t>(view().index(cell))]; }
  std::size_t bytes() const { return min_max_.size() * sizeof(vec2); }
  MacrocellView view() const { return MacrocellView{min_max_.data(), dims_, cell_size_}; }

 private:
  ivec3 dims_{0};
  int cell_size_ = kDefaultCellSize;
  std::vector<vec2> min_max_;
};

}  // namespace penumbra

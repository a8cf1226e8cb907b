#pragma once
// Empty-space skipping for an isosurface: a macrocell can hold the surface
// only where its maximum reaches the iso-value. The flags take the place of
// the TF majorants in a copy of the RenderView, so the shared macrocell walk
// (SampleCursor) skips cells entirely below the iso-value. Rebuilt per
// iso-value from the shared min/max grid: a few thousand comparisons, not a
// pass over the data.
#include "penumbra/render/render_view.h"
#include "penumbra/volume/macrocell_grid.h"

#include <cstdint>
#include <vector>

namespace penumbra {

class IsoOccupancy {
 public:
  IsoOccupancy() = default;
  IsoOccupancy(const MacrocellGrid& grid, float iso_value);

  float iso_value() const { return iso_value_; }
  // `view` with majorants 1 where a cell reaches the iso-value, 0 elsewhere.
  RenderView apply(RenderView view) const;
  std::uint64_t bytes() const { return occupied_.size() * (sizeof(float) + sizeof(std::uint8_t)); }

 private:
  float iso_value_ = 0.0f;
  std::vector<float> occupied_;
  std::vector<std::uint8_t> empty_distance_;
};

}  // namespace penumbra

#include "penumbra/techniques/occlusion_map/iso_occupancy.h"

#include "penumbra/render/majorant_grid.h"

namespace penumbra {

IsoOccupancy::IsoOccupancy(const MacrocellGrid& grid, float iso_value) : iso_value_(iso_value) {
  const MacrocellView cells = grid.view();
  const ivec3 d = grid.dims();
  occupied_.resize(std::size_t(d.x) * std::size_t(d.y) * std::size_t(d.z));
  for (std::size_t i = 0; i < occupied_.size(); ++i) occupied_[i] = cells.min_max[i].y >= iso_value ? 1.0f : 0.0f;
  empty_distance_ = empty_space_distance(occupied_, d);
}

RenderView IsoOccupancy::apply(RenderView view) const {
  view.majorants = occupied_.data();
  view.empty_distance = empty_distance_.data();
  return view;
}

}  // namespace penumbra

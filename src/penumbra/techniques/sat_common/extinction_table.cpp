#include "penumbra/techniques/sat_common/extinction_table.h"

#include "penumbra/base/parallel.h"

#include <algorithm>
#include <cmath>

namespace penumbra {

int extinction_samples_per_axis(float cell_voxels) {
  return std::max(1, int(std::ceil(2.0f * cell_voxels - 1e-3f)));
}

SummedAreaTable build_extinction_table(const RenderView& shadows, const CartesianTableGrid& grid,
                                       const std::string& what, int samples_per_axis) {
  SummedAreaTable table(grid.cells, what);
  const double cell_volume = double(grid.cell) * grid.cell * grid.cell;
  with_sampler(shadows.volume, [&](const auto& sampler) {
    const ExtinctionField<std::decay_t<decltype(sampler)>> field{&shadows, sampler};
    fill_extinction_cells(
        table, samples_per_axis, kRefineTolerance / grid.cell, field,
        [&](vec3 g) { return grid.world_from_grid(g); }, [&](int, int) { return cell_volume; });
    return 0;
  });
  table.integrate();
  return table;
}

}  // namespace penumbra

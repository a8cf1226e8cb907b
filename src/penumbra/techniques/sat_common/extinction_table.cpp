#include "penumbra/techniques/sat_common/extinction_table.h"

#include "penumbra/base/parallel.h"

namespace penumbra {

SummedAreaTable build_extinction_table(const RenderView& shadows, const CartesianTableGrid& grid,
                                       const std::string& what) {
  SummedAreaTable table(grid.cells, what);
  const double cell_volume = double(grid.cell) * grid.cell * grid.cell;
  with_sampler(shadows.volume, [&](const auto& sampler) {
    const ExtinctionField<std::decay_t<decltype(sampler)>> field{&shadows, sampler};
    parallel_for(0, std::int64_t(grid.cells.y) * grid.cells.z, [&](std::int64_t first, std::int64_t last) {
      for (std::int64_t row = first; row < last; ++row) {
        const int j = int(row % grid.cells.y);
        const int k = int(row / grid.cells.y);
        double* cells = table.cell_row(j, k);
        for (int i = 0; i < grid.cells.x; ++i) {
          cells[i] = double(field(grid.world_from_grid(vec3(i, j, k) + 0.5f))) * cell_volume;
        }
      }
    });
    return 0;
  });
  table.integrate();
  return table;
}

}  // namespace penumbra

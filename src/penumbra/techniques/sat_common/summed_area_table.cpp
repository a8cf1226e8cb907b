#include "penumbra/techniques/sat_common/summed_area_table.h"

#include "penumbra/base/error.h"
#include "penumbra/base/memory_budget.h"
#include "penumbra/base/parallel.h"

#include <fmt/format.h>

namespace penumbra {

SummedAreaTable::SummedAreaTable(ivec3 cells, const std::string& what) : cells_(cells) {
  if (cells.x < 1 || cells.y < 1 || cells.z < 1) {
    throw InvalidArgument(what, fmt::format("a summed-area table needs at least one cell per axis, got {}x{}x{}",
                                            cells.x, cells.y, cells.z));
  }
  const std::uint64_t bytes = checked_product(
      {std::uint64_t(cells.x) + 1, std::uint64_t(cells.y) + 1, std::uint64_t(cells.z) + 1, sizeof(double)});
  check_memory_budget(fmt::format("{} ({}x{}x{} cells)", what, cells.x, cells.y, cells.z), bytes);
  nodes_.assign(bytes / sizeof(double), 0.0);
}

void SummedAreaTable::integrate() {
  const std::int64_t nx = cells_.x + 1, ny = cells_.y + 1, nz = cells_.z + 1;
  double* nodes = nodes_.data();
  // x, then y, then z: each pass is a running sum along one axis, in
  // parallel over the other two, with the inner loop running along memory.
  parallel_for(0, ny * nz, [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t row = first; row < last; ++row) {
      double* r = nodes + row * nx;
      for (std::int64_t i = 1; i < nx; ++i) r[i] += r[i - 1];
    }
  });
  parallel_for(0, nz, [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t k = first; k < last; ++k) {
      double* slab = nodes + k * nx * ny;
      for (std::int64_t j = 1; j < ny; ++j) {
        for (std::int64_t i = 0; i < nx; ++i) slab[j * nx + i] += slab[(j - 1) * nx + i];
      }
    }
  });
  parallel_for(0, ny, [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t k = 1; k < nz; ++k) {
      for (std::int64_t j = first; j < last; ++j) {
        double* r = nodes + (k * ny + j) * nx;
        const double* below = r - nx * ny;
        for (std::int64_t i = 0; i < nx; ++i) r[i] += below[i];
      }
    }
  });
}

}  // namespace penumbra

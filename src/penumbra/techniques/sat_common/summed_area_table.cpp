#include "penumbra/techniques/sat_common/summed_area_table.h"

#include "penumbra/base/error.h"
#include "penumbra/base/memory_budget.h"
#include "penumbra/base/parallel.h"

#include <fmt/format.h>

#include <algorithm>

namespace penumbra {

SummedAreaTable::SummedAreaTable(ivec3 cells, const std::string& what) : cells_(cells) {
  if (cells.x < 1 || cells.y < 1 || cells.z < 1) {
    throw InvalidArgument(what, fmt::format("a summed-area table needs at least one cell per axis, got {}x{}x{}",
                                            cells.x, cells.y, cells.z));
  }
  blocks_ = (cells + (kSatBlock - 1)) / kSatBlock;
  const std::uint64_t nodes =
      checked_product({std::uint64_t(cells.x) + 1, std::uint64_t(cells.y) + 1, std::uint64_t(cells.z) + 1});
  const std::uint64_t slab = (std::uint64_t(cells.x) + 1) * (std::uint64_t(cells.y) + 1);
  const std::uint64_t corners = (std::uint64_t(blocks_.x) + 1) * (std::uint64_t(blocks_.y) + 1) *
                                (std::uint64_t(blocks_.z) + 1);
  const std::uint64_t bytes = checked_product({nodes, sizeof(float)}) + corners * sizeof(double) +
                              (kSatBlock + 1) * slab * sizeof(double);
  check_memory_budget(fmt::format("{} ({}x{}x{} cells)", what, cells.x, cells.y, cells.z), bytes);
  residuals_.assign(nodes, 0.0f);
}

void SummedAreaTable::integrate() {
  const std::int64_t nx = cells_.x + 1, ny = cells_.y + 1, nz = cells_.z + 1;
  const std::int64_t slab = nx * ny;
  const std::int64_t bx = blocks_.x + 1, by = blocks_.y + 1, bz = blocks_.z + 1;
  corners_.assign(std::size_t(bx * by * bz), 0.0);
  float* nodes = residuals_.data();
  // The exact prefix sums of the node slabs of one block layer along z, in
  // double: slab s of the layer is node slab z0 + s. Node slab z holds the
  // cells of slab z - 1 until its residuals are written, and those are
  // written only once every slab of the layer has been summed.
  std::vector<double> prefix(std::size_t((kSatBlock + 1) * slab), 0.0);
  // Node slab z from node slab z - 1 (at `below`) and the cells it holds:
  // their 2D prefix sum over x and y, plus the slab below.
  auto sum_slab = [&](std::int64_t z, const double* below, double* out) {
    const float* cells = nodes + z * slab;
    parallel_for(0, ny, [&](std::int64_t first, std::int64_t last) {
      for (std::int64_t j = first; j < last; ++j) {
        double run = 0.0;
        for (std::int64_t i = 0; i < nx; ++i) {
          run += double(cells[j * nx + i]);
          out[j * nx + i] = run;
        }
      }
    });
    parallel_for(0, nx, [&](std::int64_t first, std::int64_t last) {
      for (std::int64_t j = 1; j < ny; ++j) {
        for (std::int64_t i = first; i < last; ++i) out[j * nx + i] += out[(j - 1) * nx + i];
      }
    });
    parallel_for(0, ny, [&](std::int64_t first, std::int64_t last) {
      for (std::int64_t n = first * nx; n < last * nx; ++n) out[n] += below[n];
    });
  };
  // The block corners of one z layer from the prefix sums of its node slab.
  auto take_corners = [&](std::int64_t cz, const double* p) {
    for (std::int64_t j = 0; j < by; ++j)
      for (std::int64_t i = 0; i < bx; ++i) {
        const std::int64_t fi = std::min<std::int64_t>(i * kSatBlock, nx - 1);
        const std::int64_t fj = std::min<std::int64_t>(j * kSatBlock, ny - 1);
        corners_[std::size_t(i + bx * (j + by * cz))] = p[fi + nx * fj];
      }
  };
  // Node slab z's residuals against the trilinear base of the blocks it
  // lies in (on a block face both blocks give the same base).
  const SummedAreaTableView v = view();
  const std::int64_t strides[3] = {1, bx, bx * by};
  auto write_residuals = [&](std::int64_t z, const double* p) {
    const int ck = std::min(int(z / kSatBlock), blocks_.z - 1);
    const double tz = double(z - std::int64_t(ck) * kSatBlock) / kSatBlock;
    parallel_for(0, ny, [&](std::int64_t first, std::int64_t last) {
      for (std::int64_t j = first; j < last; ++j) {
        const int cj = std::min(int(j / kSatBlock), blocks_.y - 1);
        const double ty = double(j - std::int64_t(cj) * kSatBlock) / kSatBlock;
        for (std::int64_t i = 0; i < nx; ++i) {
          const int ci = std::min(int(i / kSatBlock), blocks_.x - 1);
          const double tx = double(i - std::int64_t(ci) * kSatBlock) / kSatBlock;
          const double t[3] = {tx, ty, tz};
          const double base = SummedAreaTableView::trilinear(corners_.data() + v.corner_index(ci, cj, ck), strides, t);
          nodes[z * slab + j * nx + i] = float(p[j * nx + i] - base);
        }
      }
    });
  };
  // Node slab 0 is zero (prefix[0..slab) already); layer by layer along z.
  take_corners(0, prefix.data());
  for (int cz = 0; cz < blocks_.z; ++cz) {
    const std::int64_t z0 = std::int64_t(cz) * kSatBlock;
    const std::int64_t z1 = std::min<std::int64_t>(z0 + kSatBlock, nz - 1);
    for (std::int64_t z = z0 + 1; z <= z1; ++z) {
      sum_slab(z, prefix.data() + (z - z0 - 1) * slab, prefix.data() + (z - z0) * slab);
    }
    take_corners(cz + 1, prefix.data() + (z1 - z0) * slab);
    // Beyond the grid the prefix sum stays that of the last node slab.
    for (std::int64_t z = z0; z < z1; ++z) write_residuals(z, prefix.data() + (z - z0) * slab);
    if (z1 == nz - 1) write_residuals(z1, prefix.data() + (z1 - z0) * slab);
    std::copy(prefix.begin() + (z1 - z0) * slab, prefix.begin() + (z1 - z0 + 1) * slab, prefix.begin());
  }
}

}  // namespace penumbra

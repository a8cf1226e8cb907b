#pragma once
// A 3D summed-area table (Crow 1984) over a grid of cells, for box sums of
// extinction in constant time (Ament et al. 2014, Schlegel et al. 2011).
//
// The table stores the prefix sums at the (cells + 1)^3 cell corners ("nodes"):
// node (i, j, k) holds the sum of every cell with index < (i, j, k), so the
// first node layer on each axis is zero. Read as a function of continuous
// grid coordinates q (cell units, corner 0 at q = 0), the prefix sum of a
// density that is constant inside each cell is exactly the trilinear
// interpolation of the nodes, so a box with arbitrary real bounds sums
// exactly with 8 trilinear reads and shadows move smoothly with the sample.
//
// Precision: the nodes are doubles, built and read in double (the "wider
// accumulators" choice). A box sum is a difference of nodes that grow with
// the whole table's mass; in float, a one-voxel box of a 256^3 table loses
// most of its digits (summed_area_table_test.cpp measures it), and Hensley et
// al.'s offset only shrinks the nodes by the table's mean, not its structure.
#include "penumbra/base/math.h"

#include <cstdint>
#include <string>
#include <vector>

namespace penumbra {

struct SummedAreaTableView {
  const double* nodes = nullptr;
  ivec3 cells{0};  // nodes per axis: cells + 1

  // The device copy (backends/device.h): the nodes mirrored.
  template <class Mirror> SummedAreaTableView on_device(Mirror& m) const {
    SummedAreaTableView d = *this;
    if (nodes) d.nodes = m.structure(nodes, std::size_t(node_index(cells.x, cells.y, cells.z)) + 1, "a summed-area table");
    return d;
  }

  PENUMBRA_HD std::int64_t node_index(int i, int j, int k) const {
    return i + std::int64_t(cells.x + 1) * (j + std::int64_t(cells.y + 1) * k);
  }

  // Sum over [0, q] of the cell-wise constant density (q in cell units,
  // clamped to the grid: outside it the density is zero).
  PENUMBRA_HD double prefix(vec3 q) const {
    q = glm::clamp(q, vec3(0.0f), vec3(cells));
    const ivec3 i0 = glm::min(ivec3(q), cells - 1);
    const double fx = double(q.x) - i0.x, fy = double(q.y) - i0.y, fz = double(q.z) - i0.z;
    const std::int64_t sy = cells.x + 1;
    const std::int64_t sz = sy * (cells.y + 1);
    const double* n = nodes + node_index(i0.x, i0.y, i0.z);
    const double x00 = n[0] + fx * (n[1] - n[0]);
    const double x10 = n[sy] + fx * (n[sy + 1] - n[sy]);
    const double x01 = n[sz] + fx * (n[sz + 1] - n[sz]);
    const double x11 = n[sy + sz] + fx * (n[sy + sz + 1] - n[sy + sz]);
    const double y0 = x00 + fy * (x10 - x00);
    const double y1 = x01 + fy * (x11 - x01);
    return y0 + fz * (y1 - y0);
  }

  // prefix(q with q[Axis] = hi) - prefix(q with q[Axis] = lo): the sum over
  // [0, q] on the other two axes and [lo, hi] on Axis. The interpolation
  // across the other two axes is shared by both ends (16 node reads instead
  // of 2 x 8, and half the arithmetic).
  template <int Axis> PENUMBRA_HD PENUMBRA_FORCE_INLINE double prefix_difference(vec3 q, float lo, float hi) const {
    constexpr int kA = Axis == 0 ? 1 : 0;
    constexpr int kB = Axis == 2 ? 1 : 2;
    const std::int64_t stride[3] = {1, std::int64_t(cells.x) + 1, (std::int64_t(cells.x) + 1) * (cells.y + 1)};
    const float a = glm::clamp(q[kA], 0.0f, float(cells[kA]));
    const float b = glm::clamp(q[kB], 0.0f, float(cells[kB]));
    lo = glm::clamp(lo, 0.0f, float(cells[Axis]));
    hi = glm::clamp(hi, 0.0f, float(cells[Axis]));
    const int ia = glm::min(int(a), cells[kA] - 1), ib = glm::min(int(b), cells[kB] - 1);
    const int il = glm::min(int(lo), cells[Axis] - 1), ih = glm::min(int(hi), cells[Axis] - 1);
    const double fa = double(a) - ia, fb = double(b) - ib, fl = double(lo) - il, fh = double(hi) - ih;
    const std::int64_t s = stride[Axis];
    const double* n = nodes + ia * stride[kA] + ib * stride[kB];
    const std::int64_t l = il * s, h = ih * s;
    auto along = [&](const double* c) {
      return (c[h] + fh * (c[h + s] - c[h])) - (c[l] + fl * (c[l + s] - c[l]));
    };
    const double d00 = along(n), d10 = along(n + stride[kA]);
    const double d01 = along(n + stride[kB]), d11 = along(n + stride[kA] + stride[kB]);
    const double d0 = d00 + fa * (d10 - d00);
    const double d1 = d01 + fa * (d11 - d01);
    return d0 + fb * (d1 - d0);
  }

  // Sum over the box [lo, hi] (grid coordinates); 0 for an empty box.
  PENUMBRA_HD PENUMBRA_FORCE_INLINE double box_sum(vec3 lo, vec3 hi) const {
    if (!(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z)) return 0.0;
    return prefix_difference<2>(hi, lo.z, hi.z) - prefix_difference<2>(vec3(lo.x, hi.y, 0.0f), lo.z, hi.z) -
           prefix_difference<2>(vec3(hi.x, lo.y, 0.0f), lo.z, hi.z) + prefix_difference<2>(lo, lo.z, hi.z);
  }
};

class SummedAreaTable {
 public:
  SummedAreaTable() = default;
  // Zero cell values on a grid of `cells` (each at least 1). Checks the node
  // memory against the budget first, naming `what` in the error.
  SummedAreaTable(ivec3 cells, const std::string& what);

  // The cell values of row (j, k), cells.x of them, to fill before
  // integrate(); rows may be filled in parallel.
  double* cell_row(int j, int k) { return nodes_.data() + view().node_index(1, j + 1, k + 1); }

  // Turns the cell values into prefix sums (in place, in parallel). Call once.
  void integrate();

  ivec3 cells() const { return cells_; }
  std::uint64_t bytes() const { return nodes_.size() * sizeof(double); }
  SummedAreaTableView view() const { return SummedAreaTableView{nodes_.data(), cells_}; }

 private:
  ivec3 cells_{0};
  std::vector<double> nodes_;
};

}  // namespace penumbra

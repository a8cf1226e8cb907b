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
// Precision (issue 22): a box sum is a difference of prefix sums that grow
// with the whole table's mass, so plain float nodes lose most of the digits
// of a one-cell box of a 256^3 table, and Hensley et al.'s offset (the
// paper's choice) only removes the table's mean, not its structure. Here each
// node is stored as a float residual against a local base: the table is cut
// into blocks of kSatBlock^3 cells, the exact prefix sums at the block
// corners are kept in double (a coarse grid, 1/kSatBlock^3 of the nodes), and
// a node stores P - B, where B is the trilinear interpolation of its block's
// eight corner sums. B is trilinear inside a block, so interpolating the
// nodes' B over a cell inside the block gives B itself: a read is the coarse
// trilinear read (double) plus the fine trilinear read of the residuals
// (float). The residuals are what the block's content adds to a linear
// ramp: the structure within a few cells, not the mass of the whole table,
// so a one-cell box keeps float's relative precision of that local
// structure (summed_area_table_test.cpp measures it: 1e-9 with doubles,
// > 1e-2 in float with the mean offset, < 1e-5 here), at a bit more than half
// the memory of double nodes.
#include "penumbra/base/math.h"

#include <cstdint>
#include <string>
#include <vector>

namespace penumbra {

// Cells per block edge of the residual layout (see above).
inline constexpr int kSatBlock = 4;

struct SummedAreaTableView {
  const float* residuals = nullptr;  // (cells + 1)^3 nodes, x fastest
  const double* corners = nullptr;   // (blocks + 1)^3 block-corner prefix sums, x fastest
  ivec3 cells{0};                    // nodes per axis: cells + 1
  ivec3 blocks{0};                   // ceil(cells / kSatBlock)

  // The device copy (backends/device.h): both arrays mirrored.
  template <class Mirror> SummedAreaTableView on_device(Mirror& m) const {
    SummedAreaTableView d = *this;
    if (residuals) {
      d.residuals = m.structure(residuals, std::size_t(node_index(cells.x, cells.y, cells.z)) + 1,
                                "a summed-area table");
      d.corners = m.structure(corners, std::size_t(corner_index(blocks.x, blocks.y, blocks.z)) + 1,
                              "a summed-area table's block corners");
    }
    return d;
  }

  PENUMBRA_HD std::int64_t node_index(int i, int j, int k) const {
    return i + std::int64_t(cells.x + 1) * (j + std::int64_t(cells.y + 1) * k);
  }
  PENUMBRA_HD std::int64_t corner_index(int i, int j, int k) const {
    return i + std::int64_t(blocks.x + 1) * (j + std::int64_t(blocks.y + 1) * k);
  }

  // Sum over [0, q] of the cell-wise constant density (q in cell units,
  // clamped to the grid: outside it the density is zero).
  PENUMBRA_HD double prefix(vec3 q) const {
    q = glm::clamp(q, vec3(0.0f), vec3(cells));
    const ivec3 i0 = glm::min(ivec3(q), cells - 1);
    const ivec3 b0 = i0 / kSatBlock;
    const double f[3] = {double(q.x) - i0.x, double(q.y) - i0.y, double(q.z) - i0.z};
    const double t[3] = {(double(q.x) - b0.x * kSatBlock) / kSatBlock, (double(q.y) - b0.y * kSatBlock) / kSatBlock,
                         (double(q.z) - b0.z * kSatBlock) / kSatBlock};
    const std::int64_t fine[3] = {1, std::int64_t(cells.x) + 1, (std::int64_t(cells.x) + 1) * (cells.y + 1)};
    const std::int64_t coarse[3] = {1, std::int64_t(blocks.x) + 1, (std::int64_t(blocks.x) + 1) * (blocks.y + 1)};
    return trilinear(corners + corner_index(b0.x, b0.y, b0.z), coarse, t) +
           trilinear(residuals + node_index(i0.x, i0.y, i0.z), fine, f);
  }

  // prefix(q with q[Axis] = hi) - prefix(q with q[Axis] = lo): the sum over
  // [0, q] on the other two axes and [lo, hi] on Axis. The interpolation
  // across the other two axes is shared by both ends (16 node reads instead
  // of 2 x 8, and half the arithmetic), for the block corners and the
  // residuals alike.
  template <int Axis> PENUMBRA_HD PENUMBRA_FORCE_INLINE double prefix_difference(vec3 q, float lo, float hi) const {
    constexpr int kA = Axis == 0 ? 1 : 0;
    constexpr int kB = Axis == 2 ? 1 : 2;
    const float a = glm::clamp(q[kA], 0.0f, float(cells[kA]));
    const float b = glm::clamp(q[kB], 0.0f, float(cells[kB]));
    lo = glm::clamp(lo, 0.0f, float(cells[Axis]));
    hi = glm::clamp(hi, 0.0f, float(cells[Axis]));
    const int ia = glm::min(int(a), cells[kA] - 1), ib = glm::min(int(b), cells[kB] - 1);
    const int il = glm::min(int(lo), cells[Axis] - 1), ih = glm::min(int(hi), cells[Axis] - 1);
    const int ja = ia / kSatBlock, jb = ib / kSatBlock, jl = il / kSatBlock, jh = ih / kSatBlock;
    constexpr double kInv = 1.0 / kSatBlock;
    const std::int64_t fine[3] = {1, std::int64_t(cells.x) + 1, (std::int64_t(cells.x) + 1) * (cells.y + 1)};
    const std::int64_t coarse[3] = {1, std::int64_t(blocks.x) + 1, (std::int64_t(blocks.x) + 1) * (blocks.y + 1)};
    const double base = column_difference(corners + ja * coarse[kA] + jb * coarse[kB], coarse[kA], coarse[kB],
                                          coarse[Axis], jl, jh, (double(a) - ja * kSatBlock) * kInv,
                                          (double(b) - jb * kSatBlock) * kInv, (double(lo) - jl * kSatBlock) * kInv,
                                          (double(hi) - jh * kSatBlock) * kInv);
    const double local = column_difference(residuals + ia * fine[kA] + ib * fine[kB], fine[kA], fine[kB], fine[Axis],
                                           il, ih, double(a) - ia, double(b) - ib, double(lo) - il, double(hi) - ih);
    return base + local;
  }

  // Sum over the box [lo, hi] (grid coordinates); 0 for an empty box.
  PENUMBRA_HD PENUMBRA_FORCE_INLINE double box_sum(vec3 lo, vec3 hi) const {
    if (!(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z)) return 0.0;
    return prefix_difference<2>(hi, lo.z, hi.z) - prefix_difference<2>(vec3(lo.x, hi.y, 0.0f), lo.z, hi.z) -
           prefix_difference<2>(vec3(hi.x, lo.y, 0.0f), lo.z, hi.z) + prefix_difference<2>(lo, lo.z, hi.z);
  }

  // Trilinear interpolation of the 8 values at n + {0, 1} strides.
  template <class T>
  PENUMBRA_HD PENUMBRA_FORCE_INLINE static double trilinear(const T* n, const std::int64_t (&s)[3],
                                                            const double (&f)[3]) {
    auto at = [&](std::int64_t o) PENUMBRA_FORCE_INLINE_LAMBDA { return double(n[o]); };
    const double x00 = at(0) + f[0] * (at(s[0]) - at(0));
    const double x10 = at(s[1]) + f[0] * (at(s[1] + s[0]) - at(s[1]));
    const double x01 = at(s[2]) + f[0] * (at(s[2] + s[0]) - at(s[2]));
    const double x11 = at(s[1] + s[2]) + f[0] * (at(s[1] + s[2] + s[0]) - at(s[1] + s[2]));
    const double y0 = x00 + f[1] * (x10 - x00);
    const double y1 = x01 + f[1] * (x11 - x01);
    return y0 + f[2] * (y1 - y0);
  }
 private:
  // Over the 4 columns at n + {0, sa} + {0, sb}: the value interpolated
  // along the column (stride s) at cell h, fraction fh, minus that at cell l,
  // fraction fl; then bilinear across the columns with fractions fa, fb.
  template <class T>
  PENUMBRA_HD PENUMBRA_FORCE_INLINE static double column_difference(const T* n, std::int64_t sa, std::int64_t sb,
                                                                    std::int64_t s, int l, int h, double fa,
                                                                    double fb, double fl, double fh) {
    const std::int64_t ol = l * s, oh = h * s;
    auto along = [&](const T* c) PENUMBRA_FORCE_INLINE_LAMBDA {
      return (double(c[oh]) + fh * (double(c[oh + s]) - double(c[oh]))) -
             (double(c[ol]) + fl * (double(c[ol + s]) - double(c[ol])));
    };
    const double d00 = along(n), d10 = along(n + sa);
    const double d01 = along(n + sb), d11 = along(n + sa + sb);
    const double d0 = d00 + fa * (d10 - d00);
    const double d1 = d01 + fa * (d11 - d01);
    return d0 + fb * (d1 - d0);
  }
};

class SummedAreaTable {
 public:
  SummedAreaTable() = default;
  // Zero cell values on a grid of `cells` (each at least 1). Checks the
  // memory (the float nodes, the block corners and integrate()'s working
  // slabs) against the budget first, naming `what` in the error.
  SummedAreaTable(ivec3 cells, const std::string& what);

  // The cell values of row (j, k), cells.x of them, to fill before
  // integrate(); rows may be filled in parallel. (They live in the nodes'
  // memory, one node up on each axis.)
  float* cell_row(int j, int k) { return residuals_.data() + view().node_index(1, j + 1, k + 1); }
  const float* cell_row(int j, int k) const { return residuals_.data() + view().node_index(1, j + 1, k + 1); }

  // Turns the cell values into prefix sums, in double one slab of nodes at
  // a time, and stores them in place as block corners and float residuals.
  // Call once.
  void integrate();

  ivec3 cells() const { return cells_; }
  std::uint64_t bytes() const { return residuals_.size() * sizeof(float) + corners_.size() * sizeof(double); }
  SummedAreaTableView view() const {
    return SummedAreaTableView{residuals_.empty() ? nullptr : residuals_.data(),
                               corners_.empty() ? nullptr : corners_.data(), cells_, blocks_};
  }

 private:
  ivec3 cells_{0};
  ivec3 blocks_{0};
  std::vector<float> residuals_;  // the cell values until integrate()
  std::vector<double> corners_;
};

}  // namespace penumbra

#pragma once
// Filtered optical depth toward a directional light from its light-aligned
// CSAT (Ament et al. 2014, section 4.2): the cuboid C of eq. 10 runs from the
// sample's plane (orthogonal to the light) to the table's face toward the
// light, over the patch [-S, S]^2 around the sample; its extinction integral
// divided by the patch area is the box-filtered optical depth (eq. 13). The
// Gaussian sums the same cuboid as taps x taps sub-cuboids C_ij, each divided
// by its own area and weighted (eq. 25). Sub-cuboids share their corner
// columns, so the box needs 4 columns and the Gaussian (taps + 1)^2, each a
// difference of two prefix sums along the light axis.
#include "penumbra/techniques/filtered_sat/shadow_filter.h"
#include "penumbra/techniques/sat_common/cartesian_table_grid.h"
#include "penumbra/techniques/sat_common/summed_area_table.h"

namespace penumbra {

// The filter's combination of light-axis columns into the filtered optical
// depth at the patch centre (a, b) (cell units, half-width `half` cells):
// column(a, b) is the extinction integral over [0, a] x [0, b] times the
// cuboid's extent along the light. Shared by the table lookup below and the
// streamed evaluation (streamed_table.h), which read their columns differently.
template <class Column>
PENUMBRA_HD PENUMBRA_FORCE_INLINE float csat_patch_depth(const Column& column, float a, float b, float half,
                                                        float cell, const ShadowFilter& filter) {
  if (filter.taps == 1) {
    const double sum = column(a + half, b + half) - column(a - half, b + half) - column(a + half, b - half) +
                       column(a - half, b - half);
    const double area = double(2.0f * half * cell) * double(2.0f * half * cell);
    return float(glm::max(sum / area, 0.0));
  }
  const float step = 2.0f * half / float(filter.taps);
  double previous[ShadowFilter::kMaxTaps + 1];
  double current[ShadowFilter::kMaxTaps + 1];
  double depth = 0.0;
  for (int j = 0; j <= filter.taps; ++j) {
    const float v = b - half + float(j) * step;
    for (int i = 0; i <= filter.taps; ++i) current[i] = column(a - half + float(i) * step, v);
    if (j > 0) {
      double row = 0.0;
      for (int i = 0; i < filter.taps; ++i) {
        row += double(filter.weights[i]) * (current[i + 1] - current[i] - previous[i + 1] + previous[i]);
      }
      depth += double(filter.weights[j - 1]) * row;
    }
    for (int i = 0; i <= filter.taps; ++i) previous[i] = current[i];
  }
  const double sub_area = double(step * cell) * double(step * cell);
  return float(glm::max(depth / sub_area, 0.0));
}

// The lookup with the light along grid axis Axis (a compile-time index, so
// that the coordinates stay in registers); q: the sample in grid coordinates.
template <int Axis>
PENUMBRA_HD PENUMBRA_FORCE_INLINE float csat_filtered_depth_along(const SummedAreaTableView& table, const CartesianTableGrid& grid,
                                                   float sign, const ShadowFilter& filter, vec3 q) {
  constexpr int kA = Axis == 0 ? 1 : 0;
  constexpr int kB = Axis == 2 ? 1 : 2;
  // The cuboid's extent along the light axis, from the sample (moved
  // `offset` toward the light) to the table's face, clamped to the grid.
  const float end = float(grid.cells[Axis]);
  const float start = q[Axis] + sign * filter.offset / grid.cell;
  const float w0 = sign > 0.0f ? glm::max(start, 0.0f) : 0.0f;
  const float w1 = sign > 0.0f ? end : glm::min(start, end);
  if (!(w1 > w0)) return 0.0f;  // beyond the table on the light side: nothing in between
  const float half = filter.half_width / grid.cell;
  // column(a, b): the extinction integral over [0, a] x [0, b] x [w0, w1].
  auto column = [&](float a, float b) PENUMBRA_FORCE_INLINE_LAMBDA {
    vec3 c(0.0f);
    c[kA] = a;
    c[kB] = b;
    return table.prefix_difference<Axis>(c, w0, w1);
  };
  return csat_patch_depth(column, q[kA], q[kB], half, grid.cell, filter);
}

// `axis`, `sign`: the light lies toward sign * grid.axes[axis].
PENUMBRA_HD inline float csat_filtered_depth(const SummedAreaTableView& table, const CartesianTableGrid& grid,
                                             int axis, float sign, const ShadowFilter& filter, vec3 p) {
  const vec3 q = grid.grid_from_world(p);
  switch (axis) {
    case 0: return csat_filtered_depth_along<0>(table, grid, sign, filter, q);
    case 1: return csat_filtered_depth_along<1>(table, grid, sign, filter, q);
    default: return csat_filtered_depth_along<2>(table, grid, sign, filter, q);
  }
}

}  // namespace penumbra

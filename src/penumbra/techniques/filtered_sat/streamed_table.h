#pragma once
// A light's filtered optical depth at a batch of points without its whole
// table (issue 22: a rotated light's CSAT over a 512^3 volume takes 1.71 GiB
// in float, an outside point light's SSAT about as much: more than the
// volume, the caches and the rest of the process together).
//
// Both lookups read their table at two depths along the light only: the
// CSAT (csat_lookup.h) at the sample's and at the table's face toward the
// light, the SSAT (ssat_lookup.h) at the pyramid's end radius and at r = 0,
// the light's side. So the stream keeps the sums counted from the light's
// side, one node layer at a time: node layer n holds, over [0, a] x [0, b]
// across the light, the extinction of the first n cell layers seen from
// the light. Layer n + 1 is layer n plus the 2D summed-area table of cell
// layer n, so two node layers (in double) and three layers of cell values
// (for the refinement of surface cells, extinction_table.h) are all that
// lives. The points are sorted by the node layer their lookup ends in (a
// counting sort, 8 bytes per point), and each is evaluated while its two
// layers live. The cells hold exactly the values the table builds give
// them; the sums are exact in double where the table stores float
// residuals, so the depths agree with the table's to its rounding
// (streamed_table_test.cpp).
//
// The price is time: every batch streams through the whole volume again
// (the extinction is sampled as for one table build), and filtered-sat
// evaluates three or four batches per light (its cache, the bricks'
// probes, the bricks, its floor grids). It streams only where a table
// would be released after its cache is filled anyway (filtered_sat.h).
#include "penumbra/render/render_view.h"
#include "penumbra/techniques/filtered_sat/csat_lookup.h"
#include "penumbra/techniques/filtered_sat/light_tables.h"

#include "penumbra/base/parallel.h"

#include <cstdint>
#include <functional>
#include <vector>

namespace penumbra {

// Two successive node layers of the stream: `lower` holds the sums of the
// first n cell layers from the light, `upper` of n + 1; each has
// (cells_a + 1) x (cells_b + 1) nodes, a fastest, the first row and column 0.
struct SatLayerPair {
  const double* lower = nullptr;
  const double* upper = nullptr;
  int cells_a = 1, cells_b = 1;
  int n = 0;

  // The extinction over [0, a] x [0, b] x the first d cell layers from the
  // light (n <= d <= n + 1), bilinear across the layers as the table reads.
  PENUMBRA_HD PENUMBRA_FORCE_INLINE double column(float a, float b, double f) const {
    a = glm::clamp(a, 0.0f, float(cells_a));
    b = glm::clamp(b, 0.0f, float(cells_b));
    const int ia = glm::min(int(a), cells_a - 1), ib = glm::min(int(b), cells_b - 1);
    const double fa = double(a) - ia, fb = double(b) - ib;
    const std::int64_t stride = cells_a + 1;
    const std::int64_t i00 = ia + stride * ib;
    auto at = [&](std::int64_t i) PENUMBRA_FORCE_INLINE_LAMBDA { return lower[i] + f * (upper[i] - lower[i]); };
    const double d00 = at(i00), d10 = at(i00 + 1), d01 = at(i00 + stride), d11 = at(i00 + stride + 1);
    const double d0 = d00 + fa * (d10 - d00);
    const double d1 = d01 + fa * (d11 - d01);
    return d0 + fb * (d1 - d0);
  }
};

// How far, in cells along the light axis, the cuboid of the point at grid
// coordinates q reaches from the table's face toward the light (<= 0:
// nothing between the point and the light), as csat_filtered_depth_along
// bounds it.
PENUMBRA_HD inline float csat_light_distance(const CartesianTableGrid& grid, int axis, float sign,
                                             const ShadowFilter& filter, vec3 q) {
  const float end = float(grid.cells[axis]);
  const float start = q[axis] + sign * filter.offset / grid.cell;
  return sign > 0.0f ? end - glm::max(start, 0.0f) : glm::min(start, end);
}

// The node layer whose pair evaluates a point at distance d (> 0).
PENUMBRA_HD inline int stream_layer_of(float d, int layers) { return glm::min(int(d), layers - 1); }

// The filtered optical depth (without the density scale) of the point at
// grid coordinates q, at distance d (> 0) from the face, from the pair of
// node layer stream_layer_of(d).
PENUMBRA_HD inline float streamed_csat_depth(const SatLayerPair& pair, const CartesianTableGrid& grid, int axis,
                                             const ShadowFilter& filter, vec3 q, float d) {
  const int ka = axis == 0 ? 1 : 0;
  const int kb = axis == 2 ? 1 : 2;
  const double f = double(glm::min(d, float(grid.cells[axis]))) - double(pair.n);
  auto column = [&](float a, float b) PENUMBRA_FORCE_INLINE_LAMBDA { return pair.column(a, b, f); };
  return csat_patch_depth(column, q[ka], q[kb], filter.half_width / grid.cell, grid.cell, filter);
}

// How far, in cells along r, the pyramid of the point at spherical
// coordinates s reaches from the table's near end (<= 0: nothing between
// the point and the light), as ssat_filtered_depth bounds it.
PENUMBRA_HD inline float ssat_light_distance(const SphericalTableGrid& grid, const ShadowFilter& filter, vec3 s) {
  const float end = ssat_pyramid_end(filter, s);
  return end > 0.0f ? glm::min((end - grid.lower.z) / grid.cell.z, float(grid.cells.z)) : 0.0f;
}

// The same for a point light's pyramid at spherical coordinates s, at
// distance d (> 0) from the near end, from the pair of node layer
// stream_layer_of(d).
PENUMBRA_HD inline float streamed_ssat_depth(const SatLayerPair& pair, const SphericalTableGrid& grid,
                                             const ShadowFilter& filter, vec3 s, float d) {
  const double f = double(d) - double(pair.n);
  auto prefix = [&](vec3 q) PENUMBRA_FORCE_INLINE_LAMBDA { return pair.column(q.x, q.y, f); };
  return ssat_filtered_depth_with(prefix, grid, filter, s, ssat_pyramid_end(filter, s));
}

class StreamedLightTable {
 public:
  // `light`: a Cartesian or spherical lookup
  // (LightTables::lookup_without_table), whose grid (and a CSAT's axis and
  // sign) the stream follows; samples_per_axis as for the table builds.
  StreamedLightTable(const RenderView& shadows, const LightTableLookup& light, int samples_per_axis)
      : shadows_(shadows), light_(light), samples_(samples_per_axis) {}

  // out[i] = the filtered optical depth at point(i) (world), i < count,
  // without the density scale: what filtered_optical_depth reads from the
  // light's whole table. Throws OutOfMemoryBudget when the point order or
  // the layers do not fit.
  template <class Point>
  void depths(const ShadowFilter& filter, std::int64_t count, const Point& point, float* out) const;

  // The bytes the stream holds besides the points' order: its layers.
  std::uint64_t layer_bytes() const;

 private:
  // visit(pair) for node layers n = 0 .. until - 1, nearest the light first.
  void stream(int until, const std::function<void(const SatLayerPair&)>& visit) const;
  // The bytes of a point order of `count` points, checked against the budget.
  static void check_order(std::int64_t count);

  RenderView shadows_;
  LightTableLookup light_;
  int samples_ = 1;
};

template <class Point>
void StreamedLightTable::depths(const ShadowFilter& filter, std::int64_t count, const Point& point, float* out) const {
  if (count <= 0) return;
  check_order(count);
  const bool cartesian = light_.kind == LightTableKind::Cartesian;
  const CartesianTableGrid& grid = light_.cartesian;
  const SphericalTableGrid& sphere = light_.spherical;
  const int axis = light_.axis;
  const float sign = light_.sign;
  const int layers = cartesian ? grid.cells[axis] : sphere.cells.z;
  // The point's distance from the light's side of the table, in cells
  // along the light, and its lookup coordinates (grid or spherical).
  auto locate = [&](std::int64_t i, vec3& q) {
    if (cartesian) {
      q = grid.grid_from_world(point(i));
      return csat_light_distance(grid, axis, sign, filter, q);
    }
    q = sphere.spherical_from_world(point(i));
    return ssat_light_distance(sphere, filter, q);
  };
  // Each point's layer (-1: nothing toward the light), then the points in
  // layer order.
  std::vector<std::int32_t> layer(static_cast<std::size_t>(count));
  parallel_for(0, count, [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t i = first; i < last; ++i) {
      vec3 q;
      const float d = locate(i, q);
      layer[std::size_t(i)] = d > 0.0f ? stream_layer_of(d, layers) : -1;
      if (!(d > 0.0f)) out[i] = 0.0f;
    }
  });
  std::vector<std::int64_t> begin(std::size_t(layers) + 1, 0);
  for (const std::int32_t n : layer) {
    if (n >= 0) ++begin[std::size_t(n) + 1];
  }
  for (int n = 0; n < layers; ++n) begin[std::size_t(n) + 1] += begin[std::size_t(n)];
  std::vector<std::uint32_t> order(static_cast<std::size_t>(begin.back()));
  {
    std::vector<std::int64_t> next(begin.begin(), begin.end() - 1);
    for (std::int64_t i = 0; i < count; ++i) {
      const std::int32_t n = layer[std::size_t(i)];
      if (n >= 0) order[std::size_t(next[std::size_t(n)]++)] = std::uint32_t(i);
    }
  }
  std::vector<std::int32_t>().swap(layer);
  // The stream stops after the deepest layer that has points.
  int until = layers;
  while (until > 0 && begin[std::size_t(until)] == begin[std::size_t(until) - 1]) --until;
  stream(until, [&](const SatLayerPair& pair) {
    const std::int64_t first_point = begin[std::size_t(pair.n)], end_point = begin[std::size_t(pair.n) + 1];
    parallel_for(first_point, end_point, [&](std::int64_t first, std::int64_t last) {
      for (std::int64_t k = first; k < last; ++k) {
        const std::int64_t i = std::int64_t(order[std::size_t(k)]);
        vec3 q;
        const float d = locate(i, q);
        out[i] = cartesian ? streamed_csat_depth(pair, grid, axis, filter, q, d)
                           : streamed_ssat_depth(pair, sphere, filter, q, d);
      }
    });
  });
}

}  // namespace penumbra

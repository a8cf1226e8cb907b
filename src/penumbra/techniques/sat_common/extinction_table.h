#pragma once
// Filling summed-area tables with extinction. Every table in the SAT
// techniques integrates the shadow transfer function's sigma_t of the
// trilinearly interpolated volume, zero outside the volume box and the clip
// planes, sampled at cell centres (the "discrete positions x_ijk" of Ament et
// al. 2014, eq. 12) and, where a cell's centre differs much from a
// neighbour's (at a surface), averaged over n^3 points inside the cell.
//
// Why the average (issue 22): a table's density is constant per cell. A
// surface that crosses the cells of a table rotated against it (any light
// off the data axes) becomes a staircase of whole cells when they hold
// their centre's value, and the material a patch of about one cell finds
// under a lit surface then jumps with the sample's position in its cell:
// a pattern with the period of one cell at small filters. Cells that hold
// the fraction of the surface inside them turn the staircase into a ramp
// (cell_pattern_test.cpp measures the pattern's energy on a cut face: 1.22
// L*^2 with centre samples at filter 1, 0.059 with 2^3 samples).
#include "penumbra/render/render_view.h"
#include "penumbra/techniques/sat_common/cartesian_table_grid.h"
#include "penumbra/techniques/sat_common/summed_area_table.h"

#include "penumbra/base/parallel.h"

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace penumbra {

// sigma_t at a world position as shadows see it. Empty macrocells return 0
// without sampling the volume (their majorant is a conservative bound).
template <class Sampler> struct ExtinctionField {
  const RenderView* view;
  Sampler sampler;

  PENUMBRA_HD float operator()(vec3 world) const {
    const RenderView& v = *view;
    if (!v.box.contains(world) || !inside_clip_planes(world, v.clip_planes, v.clip_plane_count)) return 0.0f;
    const vec3 index = v.volume.index_from_world(world);
    if (v.majorant_at(index) <= 0.0f) return 0.0f;
    return v.tf.lookup(sampler(index)).a;
  }
};

// Cells are refined where the optical depth across one cell differs from a
// neighbour's by more than this: at surfaces, not in smooth media. (At 0.01
// most cells of smooth data were refined too, and the lookups' error against
// the continuous integral rose 1.7x: inside smooth media the centre values'
// midpoint rule does better there, though each cell's own mean is closer.)
inline constexpr float kRefineTolerance = 0.1f;

// Whether a cell whose centre holds v is refined for a face neighbour's
// centre value w (fill_extinction_cells; filtered-sat's streamed tables).
inline bool extinction_cells_differ(double v, double w, float tolerance) {
  return std::abs(w - v) > double(tolerance);
}

// The mean of field(point(cell + sub)) over the n^3 sub-cell centres sub of
// the cell at grid coordinates `cell` (its lower corner).
template <class Field, class Point>
float refined_extinction_mean(const Field& field, const Point& point, vec3 cell, int n) {
  double sum = 0.0;
  for (int s = 0; s < n * n * n; ++s) {
    const vec3 sub((float(s % n) + 0.5f) / float(n), (float((s / n) % n) + 0.5f) / float(n),
                   (float(s / (n * n)) + 0.5f) / float(n));
    sum += double(field(point(cell + sub)));
  }
  return float(sum / double(n * n * n));
}

// The sub-cell points per axis that put samples at most half a voxel apart
// in a table of `cell_voxels` voxels per cell (at least 1).
int extinction_samples_per_axis(float cell_voxels);

// Fills the cells of `table` (before integrate()) with sigma_t times
// measure(j, k): first at each cell centre, then, for cells whose centre
// sigma_t differs from a face neighbour's by more than `tolerance` (per
// world unit), the mean over samples_per_axis^3 points spread evenly over
// the cell. point(g) is the world position of grid coordinate g (cell
// units); field(world) is sigma_t there.
template <class Field, class Point, class Measure>
void fill_extinction_cells(SummedAreaTable& table, int samples_per_axis, float tolerance, const Field& field,
                           const Point& point, const Measure& measure);

// A table on `grid` whose cell (i, j, k) holds its mean sigma_t times
// cell^3 (see fill_extinction_cells), so a box sum is the extinction
// integral over the box (world units). `what` names the table in
// memory-budget errors.
SummedAreaTable build_extinction_table(const RenderView& shadows, const CartesianTableGrid& grid,
                                       const std::string& what, int samples_per_axis = 1);

template <class Field, class Point, class Measure>
void fill_extinction_cells(SummedAreaTable& table, int samples_per_axis, float tolerance, const Field& field,
                           const Point& point, const Measure& measure) {
  const ivec3 cells = table.cells();
  const std::int64_t rows = std::int64_t(cells.y) * cells.z;
  parallel_for(0, rows, [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t row = first; row < last; ++row) {
      const int j = int(row % cells.y), k = int(row / cells.y);
      float* c = table.cell_row(j, k);
      for (int i = 0; i < cells.x; ++i) c[i] = field(point(vec3(i, j, k) + 0.5f));
    }
  });
  const int n = samples_per_axis;
  if (n > 1) {
    // Which cells to refine, one bit each, rows padded to whole words so
    // that rows can be flagged in parallel; then the refinement, which
    // reads no neighbour.
    const std::int64_t words = (cells.x + 63) / 64;
    std::vector<std::uint64_t> refine(std::size_t(rows * words), 0);
    parallel_for(0, rows, [&](std::int64_t first, std::int64_t last) {
      for (std::int64_t row = first; row < last; ++row) {
        const int j = int(row % cells.y), k = int(row / cells.y);
        const float* c = table.cell_row(j, k);
        const float* ym = j > 0 ? table.cell_row(j - 1, k) : nullptr;
        const float* yp = j + 1 < cells.y ? table.cell_row(j + 1, k) : nullptr;
        const float* zm = k > 0 ? table.cell_row(j, k - 1) : nullptr;
        const float* zp = k + 1 < cells.z ? table.cell_row(j, k + 1) : nullptr;
        for (int i = 0; i < cells.x; ++i) {
          const double v = c[i];
          auto differs = [&](double w) { return extinction_cells_differ(v, w, tolerance); };
          const bool edge = (i > 0 && differs(c[i - 1])) || (i + 1 < cells.x && differs(c[i + 1])) ||
                            (ym && differs(ym[i])) || (yp && differs(yp[i])) || (zm && differs(zm[i])) ||
                            (zp && differs(zp[i]));
          if (edge) refine[std::size_t(row * words + i / 64)] |= std::uint64_t(1) << (i % 64);
        }
      }
    });
    parallel_for(0, rows, [&](std::int64_t first, std::int64_t last) {
      for (std::int64_t row = first; row < last; ++row) {
        const int j = int(row % cells.y), k = int(row / cells.y);
        float* c = table.cell_row(j, k);
        for (int i = 0; i < cells.x; ++i) {
          if (!(refine[std::size_t(row * words + i / 64)] >> (i % 64) & 1)) continue;
          c[i] = refined_extinction_mean(field, point, vec3(i, j, k), n);
        }
      }
    });
  }
  parallel_for(0, rows, [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t row = first; row < last; ++row) {
      const int j = int(row % cells.y), k = int(row / cells.y);
      const double m = measure(j, k);
      float* c = table.cell_row(j, k);
      for (int i = 0; i < cells.x; ++i) c[i] = float(double(c[i]) * m);
    }
  });
}

}  // namespace penumbra

#include "penumbra/techniques/filtered_sat/streamed_table.h"

#include "penumbra/base/error.h"
#include "penumbra/base/memory_budget.h"
#include "penumbra/techniques/filtered_sat/spherical_table_grid.h"
#include "penumbra/techniques/sat_common/extinction_table.h"

#include <cmath>
#include <limits>
#include <utility>

namespace penumbra {

namespace {

// What the stream walks: cells[axis] layers of cells[ka] x cells[kb] cells
// (ka before kb in the node layers); cell layer k from the light at grid
// index reversed ? layers - 1 - k : k along the axis; world(g) the world
// point of grid coordinate g; measure(a, b) a cell's measure (volume, or
// solid angle times dr); tolerance as fill_extinction_cells takes it.
struct LayerGeometry {
  ivec3 cells{1};
  int axis = 2, ka = 0, kb = 1;
  bool reversed = false;
  float tolerance = 0.0f;
};

int axis_of(const LightTableLookup& light) { return light.kind == LightTableKind::Cartesian ? light.axis : 2; }

}  // namespace

std::uint64_t StreamedLightTable::layer_bytes() const {
  const bool cartesian = light_.kind == LightTableKind::Cartesian;
  const ivec3 c = cartesian ? light_.cartesian.cells : light_.spherical.cells;
  const int axis = axis_of(light_);
  const std::uint64_t na = std::uint64_t(c[axis == 0 ? 1 : 0]), nb = std::uint64_t(c[axis == 2 ? 1 : 2]);
  // Three layers of centres and one of cell values (float); two node
  // layers and the row sums (double).
  return 4 * na * nb * sizeof(float) + 3 * (na + 1) * (nb + 1) * sizeof(double);
}

void StreamedLightTable::check_order(std::int64_t count) {
  if (std::uint64_t(count) > std::numeric_limits<std::uint32_t>::max()) {
    throw OutOfMemoryBudget("filtered-sat's streamed table: the points' order", std::uint64_t(count) * 8,
                            memory_budget_bytes());
  }
  check_memory_budget("filtered-sat's streamed table: the points' order (lower cache_resolution)",
                      checked_product({std::uint64_t(count), 8}));
}

// The stream over one geometry: see StreamedLightTable::stream.
template <class World, class Measure>
static void stream_layers(const RenderView& shadows, const LayerGeometry& g, int samples, int until,
                          const World& world, const Measure& measure,
                          const std::function<void(const SatLayerPair&)>& visit) {
  const int axis = g.axis, ka = g.ka, kb = g.kb;
  const int layers = g.cells[axis], na = g.cells[ka], nb = g.cells[kb];
  const std::size_t cells = std::size_t(na) * std::size_t(nb);
  const std::size_t nodes = std::size_t(na + 1) * std::size_t(nb + 1);
  std::vector<float> previous(cells), current(cells), next(cells), values(cells);
  std::vector<double> lower(nodes, 0.0), upper(nodes, 0.0), rows(nodes, 0.0);
  const float tolerance = g.tolerance;
  const int n = samples;
  auto grid_layer = [&](int k) { return g.reversed ? layers - 1 - k : k; };
  auto index = [&](int a, int b, int layer) {
    vec3 i(0.0f);
    i[ka] = float(a);
    i[kb] = float(b);
    i[axis] = float(layer);
    return i;
  };
  with_sampler(shadows.volume, [&](const auto& sampler) {
    const ExtinctionField<std::decay_t<decltype(sampler)>> field{&shadows, sampler};
    auto centres = [&](int k, std::vector<float>& out) {
      const int layer = grid_layer(k);
      parallel_for(0, nb, [&](std::int64_t first, std::int64_t last) {
        for (std::int64_t b = first; b < last; ++b) {
          for (int a = 0; a < na; ++a) {
            out[std::size_t(a) + std::size_t(na) * std::size_t(b)] = field(world(index(a, int(b), layer) + 0.5f));
          }
        }
      });
    };
    centres(0, current);
    for (int k = 0; k < until; ++k) {
      if (k + 1 < layers) centres(k + 1, next);
      const int layer = grid_layer(k);
      // The cell values as fill_extinction_cells gives them: the centre, or
      // in a cell that differs from a face neighbour by more than the
      // tolerance the mean over n^3 points, times the cell's measure.
      parallel_for(0, nb, [&](std::int64_t first, std::int64_t last) {
        for (std::int64_t b = first; b < last; ++b) {
          for (int a = 0; a < na; ++a) {
            const std::size_t c = std::size_t(a) + std::size_t(na) * std::size_t(b);
            const double v = current[c];
            float value = current[c];
            if (n > 1) {
              auto differs = [&](double w) { return extinction_cells_differ(v, w, tolerance); };
              const bool edge = (a > 0 && differs(current[c - 1])) || (a + 1 < na && differs(current[c + 1])) ||
                                (b > 0 && differs(current[c - std::size_t(na)])) ||
                                (b + 1 < nb && differs(current[c + std::size_t(na)])) ||
                                (k > 0 && differs(previous[c])) || (k + 1 < layers && differs(next[c]));
              if (edge) value = refined_extinction_mean(field, world, index(a, int(b), layer), n);
            }
            values[c] = float(double(value) * measure(a, int(b)));
          }
        }
      });
      // Node layer k + 1: node layer k plus the 2D summed-area table of the
      // cell layer (rows first, then down the columns).
      const std::size_t stride = std::size_t(na) + 1;
      parallel_for(0, nb, [&](std::int64_t first, std::int64_t last) {
        for (std::int64_t b = first; b < last; ++b) {
          double run = 0.0;
          double* row = rows.data() + stride * std::size_t(b + 1);
          for (int a = 0; a < na; ++a) {
            run += double(values[std::size_t(a) + std::size_t(na) * std::size_t(b)]);
            row[a + 1] = run;
          }
        }
      });
      parallel_for(1, na + 1, [&](std::int64_t first, std::int64_t last) {
        for (std::int64_t a = first; a < last; ++a) {
          double column = 0.0;
          for (int b = 1; b <= nb; ++b) {
            const std::size_t i = std::size_t(a) + stride * std::size_t(b);
            column += rows[i];
            upper[i] = lower[i] + column;
          }
        }
      });
      visit(SatLayerPair{lower.data(), upper.data(), na, nb, k});
      std::swap(lower, upper);
      std::swap(previous, current);
      std::swap(current, next);
    }
    return 0;
  });
}

void StreamedLightTable::stream(int until, const std::function<void(const SatLayerPair&)>& visit) const {
  check_memory_budget("filtered-sat's streamed table layers (lower sat_resolution)", layer_bytes());
  LayerGeometry g;
  if (light_.kind == LightTableKind::Cartesian) {
    const CartesianTableGrid& grid = light_.cartesian;
    g.cells = grid.cells;
    g.axis = light_.axis;
    g.ka = g.axis == 0 ? 1 : 0;
    g.kb = g.axis == 2 ? 1 : 2;
    g.reversed = light_.sign > 0.0f;  // the light lies toward +axis: its face is the last layer
    g.tolerance = kRefineTolerance / grid.cell;
    const double volume = double(grid.cell) * grid.cell * grid.cell;
    stream_layers(
        shadows_, g, samples_, until, [&](vec3 q) { return grid.world_from_grid(q); },
        [&](int, int) { return volume; }, visit);
    return;
  }
  // A point light's SSAT: (phi, theta) across, r along the light from its
  // near end; the measures as build_spherical_extinction_table's.
  const SphericalTableGrid& grid = light_.spherical;
  g.cells = grid.cells;
  g.tolerance = kRefineTolerance / grid.cell.z;
  stream_layers(
      shadows_, g, samples_, until, [&](vec3 q) { return grid.world_from_spherical(grid.lower + q * grid.cell); },
      [&](int, int theta) { return spherical_cell_measure(grid, theta); }, visit);
}

}  // namespace penumbra

#include "penumbra/techniques/sat_common/cartesian_table_grid.h"

#include "penumbra/base/error.h"

#include <fmt/format.h>

#include <cmath>

namespace penumbra {

CartesianTableGrid fit_cartesian_grid(const Box3& box, vec3 u, vec3 v, vec3 w, float cell) {
  if (!(cell > 0.0f) || !std::isfinite(cell)) {
    throw InvalidArgument("sat_resolution", fmt::format("the table cell must be positive, got {}", cell));
  }
  CartesianTableGrid grid;
  grid.axes[0] = u;
  grid.axes[1] = v;
  grid.axes[2] = w;
  grid.cell = cell;
  vec3 lo(kInfinity), hi(-kInfinity);
  for (int corner = 0; corner < 8; ++corner) {
    const vec3 p((corner & 1) ? box.upper.x : box.lower.x, (corner & 2) ? box.upper.y : box.lower.y,
                 (corner & 4) ? box.upper.z : box.lower.z);
    const vec3 q(glm::dot(p, u), glm::dot(p, v), glm::dot(p, w));
    lo = glm::min(lo, q);
    hi = glm::max(hi, q);
  }
  // An extent a hair above a whole number of cells (rounding) does not get
  // a whole extra cell: the box then pokes out by < 0.1% of a cell, which
  // neither the cell-centre samples nor the clamped lookups can notice.
  const vec3 extent = hi - lo;
  for (int a = 0; a < 3; ++a) grid.cells[a] = std::max(1, int(std::ceil(extent[a] / cell - 1e-3f)));
  const vec3 start = 0.5f * (lo + hi) - 0.5f * cell * vec3(grid.cells);
  grid.origin = start.x * u + start.y * v + start.z * w;
  return grid;
}

void complete_frame(vec3 w, vec3& u, vec3& v) {
  w = glm::normalize(w);
  const vec3 a = glm::abs(w);
  const vec3 axis = a.x <= a.y && a.x <= a.z ? vec3(1.0f, 0.0f, 0.0f)
                                              : (a.y <= a.z ? vec3(0.0f, 1.0f, 0.0f) : vec3(0.0f, 0.0f, 1.0f));
  u = glm::normalize(axis - glm::dot(axis, w) * w);
  v = glm::cross(w, u);
}

}  // namespace penumbra

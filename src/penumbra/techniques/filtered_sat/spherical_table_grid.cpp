#include "penumbra/techniques/filtered_sat/spherical_table_grid.h"

#include "penumbra/base/error.h"
#include "penumbra/base/parallel.h"
#include "penumbra/techniques/sat_common/cartesian_table_grid.h"
#include "penumbra/techniques/sat_common/extinction_table.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace penumbra {
namespace {

vec3 box_corner(const Box3& box, int corner) {
  return vec3((corner & 1) ? box.upper.x : box.lower.x, (corner & 2) ? box.upper.y : box.lower.y,
              (corner & 4) ? box.upper.z : box.lower.z);
}

// Angular bounds of the box seen from outside it. The box's directions form a
// convex spherical polygon bounded by its projected edges; the frame keeps it
// inside the hemisphere around axes[0], away from the poles, so phi and theta
// take their extremes on the edges, which are sampled densely (the chord
// between samples deviates from the great arc by far less than the margin
// added afterwards).
void angular_bounds(const SphericalTableGrid& grid, const Box3& box, vec2& phi, vec2& theta) {
  constexpr int kEdgeSamples = 64;
  phi = vec2(kInfinity, -kInfinity);
  theta = phi;
  for (int a = 0; a < 8; ++a) {
    for (int bit = 1; bit < 8; bit <<= 1) {
      if (a & bit) continue;
      const vec3 p = box_corner(box, a), q = box_corner(box, a | bit);
      for (int s = 0; s <= kEdgeSamples; ++s) {
        const vec3 sph = grid.spherical_from_world(glm::mix(p, q, float(s) / kEdgeSamples));
        phi = vec2(std::min(phi.x, sph.x), std::max(phi.y, sph.x));
        theta = vec2(std::min(theta.x, sph.y), std::max(theta.y, sph.y));
      }
    }
  }
  const float phi_margin = 1e-3f + 0.01f * (phi.y - phi.x);
  const float theta_margin = 1e-3f + 0.01f * (theta.y - theta.x);
  phi += vec2(-phi_margin, phi_margin);
  theta = glm::clamp(theta + vec2(-theta_margin, theta_margin), vec2(0.0f), vec2(kPi));
}

}  // namespace

SphericalTableGrid fit_spherical_grid(const Box3& box, vec3 light, float cell) {
  if (!(cell > 0.0f) || !std::isfinite(cell)) {
    throw InvalidArgument("sat_resolution", fmt::format("the table cell must be positive, got {}", cell));
  }
  SphericalTableGrid grid;
  grid.light = light;
  float r_max = 0.0f;
  for (int c = 0; c < 8; ++c) r_max = std::max(r_max, glm::length(box_corner(box, c) - light));
  const vec3 closest = glm::clamp(light, box.lower, box.upper);
  const float gap = glm::length(closest - light);
  vec2 phi, theta, radius;
  if (gap <= 0.5f * cell) {
    // Inside (or touching) the box: the whole sphere.
    grid.full_turn = true;
    phi = vec2(-kPi, kPi);
    theta = vec2(0.0f, kPi);
    radius = vec2(0.0f, r_max + 0.5f * cell);
  } else {
    // Outside: phi = 0 points at the box. Beyond the bounding sphere every
    // box direction lies within 90 degrees of the centre direction; closer,
    // within 90 degrees of the direction to the nearest box point (the box
    // lies in the half-space beyond the plane through that point).
    const vec3 to_centre = box.center() - light;
    const bool beyond = glm::length(to_centre) > 0.5f * glm::length(box.extent());
    const vec3 x = glm::normalize(beyond ? to_centre : closest - light);
    complete_frame(x, grid.axes[1], grid.axes[2]);
    grid.axes[0] = x;
    angular_bounds(grid, box, phi, theta);
    radius = vec2(std::max(0.0f, gap - 0.5f * cell), r_max + 0.5f * cell);
  }
  // Cells about `cell` wide at the middle distance; the azimuthal arc is
  // widest where sin(theta) is largest.
  const float r_mid = 0.5f * (radius.x + radius.y);
  const float sin_max = (theta.x <= 0.5f * kPi && theta.y >= 0.5f * kPi)
                            ? 1.0f
                            : std::max(std::sin(theta.x), std::sin(theta.y));
  grid.cells = ivec3(std::max(1, int(std::ceil((phi.y - phi.x) * r_mid * sin_max / cell))),
                     std::max(1, int(std::ceil((theta.y - theta.x) * r_mid / cell))),
                     std::max(1, int(std::ceil((radius.y - radius.x) / cell))));
  grid.lower = vec3(phi.x, theta.x, radius.x);
  grid.cell = vec3(phi.y - phi.x, theta.y - theta.x, radius.y - radius.x) / vec3(grid.cells);
  return grid;
}

double spherical_cell_measure(const SphericalTableGrid& grid, int j) {
  const double theta0 = double(grid.lower.y) + double(grid.cell.y) * j;
  return double(grid.cell.x) * (std::cos(theta0) - std::cos(theta0 + grid.cell.y)) * double(grid.cell.z);
}

SummedAreaTable build_spherical_extinction_table(const RenderView& shadows, const SphericalTableGrid& grid,
                                                 const std::string& what, int samples_per_axis) {
  SummedAreaTable table(grid.cells, what);
  // Cells are about this wide (world units) at the middle distance.
  const float width = grid.cell.z;
  with_sampler(shadows.volume, [&](const auto& sampler) {
    const ExtinctionField<std::decay_t<decltype(sampler)>> field{&shadows, sampler};
    fill_extinction_cells(
        table, samples_per_axis, kRefineTolerance / width, field,
        [&](vec3 g) { return grid.world_from_spherical(grid.lower + g * grid.cell); },
        [&](int j, int) { return spherical_cell_measure(grid, j); });
    return 0;
  });
  table.integrate();
  return table;
}

}  // namespace penumbra

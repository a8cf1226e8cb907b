#pragma once
// Filtered optical depth toward a point light from its spherical SAT (Ament
// et al. 2014, eqs. 16-24). The patch is the square [-S, S]^2 in the plane
// tangent to the sphere through the sample (spanned by r_phi and r_theta,
// eqs. 16-18), projected onto that sphere (eq. 20); its corners' directions
// give a box in (phi, theta): phi +- atan(S / (R sin theta)), theta +-
// atan(S / R). The spherical pyramid S of eq. 22 is that box from r = 0 (the
// light, or the table's near end) to the sample's radius R. Its table sum
// (sigma_t dr dOmega, see spherical_table_grid.h) divided by the box's solid
// angle is the mean optical depth of the light rays through the patch, the
// same for every direction ("equal base area A"). Gaussian sub-patches are
// the images of the tangent-plane sub-squares, each normalised by its own
// solid angle and weighted as in eq. 25.
#include "penumbra/techniques/filtered_sat/shadow_filter.h"
#include "penumbra/techniques/filtered_sat/spherical_table_grid.h"
#include "penumbra/techniques/sat_common/summed_area_table.h"

namespace penumbra {

// Prefix sum at (phi, theta, r), prefix(q) reading the table at grid
// coordinates q. On a whole-turn grid phi is unwrapped: every full turn
// below phi adds the sum of one complete turn, so boxes that cross the seam
// at phi = +-pi need no splitting.
template <class Prefix>
PENUMBRA_HD PENUMBRA_FORCE_INLINE double ssat_prefix_with(const Prefix& prefix, const SphericalTableGrid& grid,
                                                          float phi, float theta, float r) {
  vec3 q = grid.grid_from_spherical(vec3(phi, theta, r));
  if (!grid.full_turn) return prefix(q);
  const float turn = float(grid.cells.x);
  const float turns = glm::floor(q.x / turn);
  q.x -= turns * turn;
  const double base = prefix(q);
  return turns == 0.0f ? base : base + double(turns) * prefix(vec3(turn, q.y, q.z));
}

// The pyramid ends this far from the light (<= 0: nothing lies between
// the sample at spherical coordinates s and the light).
PENUMBRA_HD inline float ssat_pyramid_end(const ShadowFilter& filter, vec3 s) {
  return s.z > 0.0f ? s.z - filter.offset : 0.0f;
}

// The filtered depth at the sample at spherical coordinates s, whose
// pyramid ends at radius end > 0, from a table read through prefix(q) (all
// reads at end's radius: streamed_table.h reads two layers there).
template <class Prefix>
PENUMBRA_HD inline float ssat_filtered_depth_with(const Prefix& prefix, const SphericalTableGrid& grid,
                                                  const ShadowFilter& filter, vec3 s, float end) {
  const float radius = s.z;
  const float tangent_radius = radius * glm::sin(s.y);  // distance from the polar axis
  const float step = 2.0f * filter.half_width / float(filter.taps);
  double depth = 0.0, weight_sum = 0.0;
  for (int j = 0; j < filter.taps; ++j) {
    const float v0 = -filter.half_width + float(j) * step;
    const float theta0 = glm::clamp(s.y + glm::atan(v0, radius), 0.0f, kPi);
    const float theta1 = glm::clamp(s.y + glm::atan(v0 + step, radius), 0.0f, kPi);
    if (!(theta1 > theta0)) continue;
    // A sub-patch reaching a pole covers every azimuth there.
    const bool polar = theta0 <= 0.0f || theta1 >= kPi;
    for (int i = 0; i < filter.taps; ++i) {
      const float u0 = -filter.half_width + float(i) * step;
      const float phi0 = polar ? s.x - kPi : s.x + glm::atan(u0, tangent_radius);
      const float phi1 = polar ? s.x + kPi : s.x + glm::atan(u0 + step, tangent_radius);
      const double solid_angle = double(phi1 - phi0) * (double(glm::cos(theta0)) - double(glm::cos(theta1)));
      if (!(solid_angle > 0.0)) continue;
      const double sum = ssat_prefix_with(prefix, grid, phi1, theta1, end) -
                         ssat_prefix_with(prefix, grid, phi0, theta1, end) -
                         ssat_prefix_with(prefix, grid, phi1, theta0, end) +
                         ssat_prefix_with(prefix, grid, phi0, theta0, end);
      const double w = double(filter.weights[i]) * double(filter.weights[j]);
      depth += w * sum / solid_angle;
      weight_sum += w;
    }
  }
  return weight_sum > 0.0 ? float(glm::max(depth / weight_sum, 0.0)) : 0.0f;
}

PENUMBRA_HD inline float ssat_filtered_depth(const SummedAreaTableView& table, const SphericalTableGrid& grid,
                                             const ShadowFilter& filter, vec3 p) {
  const vec3 s = grid.spherical_from_world(p);
  // The pyramid ends `offset` short of the sample, toward the light.
  const float end = ssat_pyramid_end(filter, s);
  if (!(end > 0.0f)) return 0.0f;
  return ssat_filtered_depth_with([&](vec3 q) PENUMBRA_FORCE_INLINE_LAMBDA { return table.prefix(q); }, grid, filter,
                                  s, end);
}

}  // namespace penumbra

#pragma once
// The spherical SAT (SSAT) of a point light (Ament et al. 2014, section
// 4.2.3): a regular grid in spherical coordinates (phi, theta, r) about the
// light, in which light rays run parallel to the r axis. Azimuth phi is
// measured from axes[0] toward axes[1], the polar angle theta from axes[2].
//
// Coverage: a light inside the volume box gets the whole sphere (phi wraps
// around); a light outside gets only the solid angle the box subtends, with
// the frame chosen so that this solid angle stays away from the poles.
//
// Cells hold sigma_t dr dOmega = sigma_t sin(theta) dr dtheta dphi, not the
// volume element r^2 sin(theta) dr dtheta dphi of the paper's eq. 23: divided
// by the solid angle of a patch, a box sum is then exactly the mean optical
// depth of the light rays through the patch (eqs. 4 and 5), for occluders at
// any distance from the light; with r^2 dOmega / A the occluders near the
// light would be weighted by (r / R)^2 and a point light inside the volume
// would lose the shadows of everything close to it. Both agree where the
// occluders are at about the sample's distance from the light.
#include "penumbra/render/render_view.h"
#include "penumbra/techniques/sat_common/summed_area_table.h"

#include <string>

namespace penumbra {

struct SphericalTableGrid {
  vec3 light{0.0f};
  vec3 axes[3] = {vec3(1.0f, 0.0f, 0.0f), vec3(0.0f, 1.0f, 0.0f), vec3(0.0f, 0.0f, 1.0f)};
  vec3 lower{0.0f};  // (phi, theta, r) of grid coordinate 0
  vec3 cell{1.0f};   // (dphi, dtheta, dr) of one cell
  ivec3 cells{1};    // along phi, theta, r
  bool full_turn = false;  // phi covers a whole turn, so boxes wrap around

  PENUMBRA_HD vec3 spherical_from_world(vec3 p) const {
    const vec3 d = p - light;
    const float x = glm::dot(d, axes[0]), y = glm::dot(d, axes[1]), z = glm::dot(d, axes[2]);
    const float r = glm::sqrt(x * x + y * y + z * z);
    const float theta = r > 0.0f ? glm::acos(glm::clamp(z / r, -1.0f, 1.0f)) : 0.0f;
    return vec3(glm::atan(y, x), theta, r);
  }
  PENUMBRA_HD vec3 world_from_spherical(vec3 s) const {
    const float st = glm::sin(s.y);
    return light + s.z * (st * glm::cos(s.x) * axes[0] + st * glm::sin(s.x) * axes[1] + glm::cos(s.y) * axes[2]);
  }
  PENUMBRA_HD vec3 grid_from_spherical(vec3 s) const { return (s - lower) / cell; }
};

// The grid covering `box` as seen from `light`, with cells about `cell`
// world units wide at the middle of the box's distance range.
SphericalTableGrid fit_spherical_grid(const Box3& box, vec3 light, float cell);

// The measure of a cell in polar row j: dphi (cos theta_j - cos theta_j+1) dr.
double spherical_cell_measure(const SphericalTableGrid& grid, int j);

// The SSAT: cell (i, j, k) holds sigma_t at its centre times its measure
// dphi (cos theta_j - cos theta_j+1) dr. `what` names it in budget errors.
SummedAreaTable build_spherical_extinction_table(const RenderView& shadows, const SphericalTableGrid& grid,
                                                 const std::string& what, int samples_per_axis = 1);

}  // namespace penumbra

#pragma once
// The placement of a summed-area table in world space: a Cartesian grid of
// cubic cells whose axes u, v, w are any orthonormal, right-handed frame.
// With the world axes it is the volume-aligned SAT of Schlegel et al. 2011;
// with w along a light it is the light-aligned CSAT of Ament et al. 2014
// (section 4.2.1). Grid coordinates are in cell units, 0 at the grid's
// lower corner.
#include "penumbra/base/math.h"
#include "penumbra/base/ray.h"

namespace penumbra {

struct CartesianTableGrid {
  vec3 axes[3] = {vec3(1.0f, 0.0f, 0.0f), vec3(0.0f, 1.0f, 0.0f), vec3(0.0f, 0.0f, 1.0f)};  // u, v, w
  vec3 origin{0.0f};  // world position of grid coordinate (0, 0, 0)
  float cell = 1.0f;  // cell edge in world units
  ivec3 cells{1};

  PENUMBRA_HD vec3 grid_from_world(vec3 p) const {
    const vec3 d = p - origin;
    return vec3(glm::dot(d, axes[0]), glm::dot(d, axes[1]), glm::dot(d, axes[2])) / cell;
  }
  PENUMBRA_HD vec3 world_from_grid(vec3 g) const {
    return origin + cell * (g.x * axes[0] + g.y * axes[1] + g.z * axes[2]);
  }
};

// The smallest grid of cells of edge `cell` along the axes (u, v, w) whose
// box contains `box` (centred on it). Throws InvalidArgument for a
// non-positive cell.
CartesianTableGrid fit_cartesian_grid(const Box3& box, vec3 u, vec3 v, vec3 w, float cell);

// A right-handed orthonormal frame (u, v, w) with w = `w` (normalised): u is
// the world axis least aligned with w, made orthogonal to it, so a w along a
// world axis gives world-aligned axes.
void complete_frame(vec3 w, vec3& u, vec3& v);

}  // namespace penumbra

#pragma once
// Built-in closed meshes for scenes, tests and benchmarks, so a mesh scene
// needs no file. All are centred at the origin, fit in [-1, 1]^3, are closed
// (every edge in exactly two triangles) and wound counter-clockwise seen from
// outside, as scene/mesh.h requires. `resolution` sets the tessellation
// (0 = the shape's default); it is capped so a mesh stays under ~4 million
// triangles.
//
//   sphere      radius 1: a subdivided icosahedron, resolution = subdivision level (default 3, at most 8)
//   box         half-extent 1: resolution = quads along each face edge (default 1, i.e. 12 triangles)
//   torus       major radius 0.7, minor 0.3, axis z: resolution = segments around the tube (default 32),
//               twice as many around the axis
//   torus-knot  a tube of radius 0.15 around the (2,3) torus knot: resolution = segments around the tube
//               (default 16), 16 times as many along the curve
//   disk        closed cylinder of radius 1 and thickness 0.05, axis z (the occluder of Patel et al. 2013,
//               Fig. 14): resolution = segments around the rim (default 64)
#include "penumbra/scene/mesh.h"

#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace penumbra {

// Throws InvalidArgument("builtin", ...) for an unknown name and
// InvalidArgument("resolution", ...) for a resolution out of the shape's range.
std::shared_ptr<TriangleMesh> make_builtin_mesh(std::string_view name, int resolution = 0);

// (name, one-line description) of every built-in mesh, in a fixed order.
const std::vector<std::pair<std::string, std::string>>& builtin_meshes();

}  // namespace penumbra

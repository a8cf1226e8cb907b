#pragma once
// Triangle meshes from Wavefront OBJ and Stanford PLY files, for the closed
// meshes with volumetric detail of Patel et al. 2013 (scene/mesh.h).
//
// OBJ: `v x y z [w]` (a trailing vertex colour, as MeshLab writes, is allowed
// too; w is ignored as for every polygon reader) and `f` with `i`, `i/t`,
// `i//n` or `i/t/n` corners; negative indices count back from the last vertex.
// Texture coordinates, normals, groups, materials, smoothing and statements
// this reader does not know are skipped. A `\` at the end of a line continues it.
//
// PLY (http://paulbourke.net/dataformats/ply/): ascii, binary_little_endian
// and binary_big_endian; positions are the x, y, z properties of the `vertex`
// element, faces the `vertex_indices` (or `vertex_index`) list of `face`.
// Every other element and property, lists included, is skipped. Declared
// counts are checked against the file length before anything is allocated.
//
// Polygons with more than three corners become triangle fans; the winding of
// the file is kept. Malformed files throw IoError naming the path and the
// line (OBJ) or element (PLY) at fault.
#include "penumbra/scene/mesh.h"

#include <filesystem>

namespace penumbra {

// Dispatches on the extension, .obj or .ply (any case).
TriangleMesh read_mesh(const std::filesystem::path& path);

TriangleMesh read_obj(const std::filesystem::path& path);
TriangleMesh read_ply(const std::filesystem::path& path);

}  // namespace penumbra

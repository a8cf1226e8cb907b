#pragma once
// Closed triangle meshes filled with volumetric detail (Patel et al. 2013,
// section 4). A mesh bounds a region of space; inside it a detail function
// (volumetric_detail.h) of the object-space position gives a value that the
// mesh's own transfer function maps to colour and extinction, like the
// volume's TF maps voxel values. At the surface a microfacet specular term is
// added (microfacet.h). Only `convolution` draws meshes; every other technique
// leaves them out and says so (DESIGN-NOTES "Meshes").
//
// Meshes must be closed (every edge shared by exactly two triangles) so that
// a viewing ray's crossings alternate between entering and leaving; the
// triangles are wound counter-clockwise seen from outside (outward normals).
// Overlapping meshes are allowed: each keeps its own inside/outside parity and
// their media add up.
#include "penumbra/base/math.h"
#include "penumbra/base/ray.h"
#include "penumbra/scene/transfer_function.h"
#include "penumbra/scene/volumetric_detail.h"
#include "penumbra/volume/volume.h"

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace penumbra {

struct TriangleMesh {
  std::vector<vec3> positions;
  std::vector<glm::uvec3> triangles;  // indices into positions, counter-clockwise from outside

  Box3 bounds() const;  // of the positions; empty box (lower > upper) for no positions
  // Throws InvalidArgument(name, ...) for no triangles, an index out of range,
  // a position that is not finite, or a mesh that is not closed and
  // consistently wound (vertices at equal positions count as one).
  void validate(const std::string& name) const;

  // For each vertex, the lowest index of a vertex at exactly the same position
  // (-0 and +0 alike): files split vertices at UV or normal seams, and the
  // surface is the same either way.
  std::vector<std::uint32_t> welded_indices() const;

 private:
  void check_closed(const std::string& name) const;
};

enum class DetailType : std::uint8_t { Constant, Noise, Fbm, Ridged, Texture };

struct DetailFunction {
  DetailType type = DetailType::Fbm;
  float frequency = 1.0f;  // lattice cells per object-space unit (noise types)
  FractalParams fractal;   // octaves, lacunarity, gain, offset (ridged), time
  bool time_dependent = false;  // 4D noise with fractal.time as the fourth coordinate
  float value = 0.5f;           // Constant: the value everywhere
  std::string texture_file;     // Texture: a volume file as written in the scene
  std::shared_ptr<const Volume> texture;  // Texture: the loaded volume (first frame), stretched over the mesh's bounds
  std::uint64_t seed = 0;                 // the noise permutation
};

struct MeshMaterial {
  DetailFunction detail;
  // Detail value -> (colour, opacity per unit_length). Its range is in detail
  // units (default [-1, 1]; "data" means the texture's value range).
  TransferFunction tf;
  // Optional: the colour from a second detail function (Patel et al. 2013,
  // Fig. 9: a 3D texture for colour, a procedural function for opacity),
  // through color_tf's colours; the opacity stays detail's through tf.
  bool has_color_detail = false;
  DetailFunction color_detail;
  TransferFunction color_tf;
  float specular = 0.04f;  // Fresnel reflectance at normal incidence (Schlick); 0 = no highlight
  float roughness = 0.3f;  // GGX alpha, in (0, 1]
  // Optional chromatic attenuation (Patel et al. 2013, Fig. 7e, after Kniss
  // et al. 2003's transport colour): light on its way to other samples
  // attenuates per channel with sigma_t (1 - transport_color), so the medium
  // lets that colour through; along viewing rays the extinction stays grey.
  // Absent: grey (as [0, 0, 0], without the three-channel light buffers).
  std::optional<vec3> transport_color;
};

// Where a mesh came from, as a scene file names it.
struct MeshSource {
  std::string file;     // .obj or .ply, as written (relative to the scene file)
  std::string builtin;  // mesh_shapes.h
  int resolution = 0;   // builtin: tessellation level (0 = the shape's default)
};

struct MeshObject {
  MeshSource source;
  std::shared_ptr<const TriangleMesh> mesh;  // object space
  vec3 scale{1.0f};
  vec3 rotate_deg{0.0f};  // about x, then y, then z
  vec3 translate{0.0f};
  MeshMaterial material;

  // translate * Rz * Ry * Rx * scale.
  mat4 object_to_world() const;
  // The mesh's world-space bounding box.
  Box3 world_bounds() const;
};

}  // namespace penumbra

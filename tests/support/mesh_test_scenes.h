#pragma once
// Mesh scenes shared by the tests of the techniques that draw meshes
// (convolution, pathtrace, shadow-rays): homogeneous spheres whose chords are
// known in closed form, their shadow on a floor against Beer-Lambert, and a
// dense box drawn as a mesh or as the same volume.
#include "penumbra/render/image.h"
#include "penumbra/render/parameters.h"
#include "penumbra/scene/scene.h"

#include <optional>
#include <string>

namespace penumbra::testing {

inline constexpr float kMeshAlphaPerUnit = 0.1f;  // homogeneous_sphere's default TF opacity per world unit

// A sphere mesh of `radius` at `center` filled with a homogeneous white medium
// (constant detail through a constant TF of alpha `alpha` per world unit).
MeshObject homogeneous_sphere(float radius, vec3 center, float alpha = kMeshAlphaPerUnit);

// An empty 32^3 volume (box [-15.5, 15.5]^3) seen from +z by an orthographic
// camera `height` world units tall, lit by nothing but `ambient`.
Scene mesh_scene(int image, float height, float ambient);

// World (x, y) of a pixel centre for mesh_scene's camera (x right, y up).
vec2 pixel_world(int x, int y, int image, float height);

// The length of the chord of a sphere of `radius` at `offset` from its centre.
float chord(float radius, vec2 offset);

// The shadow of a sphere of radius 12 (kMeshAlphaPerUnit) on a floor 40
// below, lit by a directional light travelling (1, 0, -1), seen from above at
// 64^2, against lit * exp(-sigma chord) per colour channel: in the core
// (light rays at most 0.5 R off the centre) and on the floor more than 3
// pixels past the rim. With a transport colour t the sphere's medium
// attenuates light with sigma (1 - t) per channel.
struct FloorShadow {
  int inside = 0, outside = 0;
  float worst_inside = 0.0f, worst_outside = 0.0f;  // over the three channels
  double mean_inside = 0.0;  // signed: image minus Beer-Lambert, mean over pixels and channels
  vec3 core{0.0f};           // the mean colour of the core's pixels
};
FloorShadow sphere_floor_shadow(const std::string& technique, const ParameterSettings& params,
                                const std::string& image_name, std::optional<vec3> transport_color = {});

// A dense homogeneous box (sigma 4.6 per unit: alpha 0.99 per unit), seen
// obliquely by an orthographic camera and lit from behind the viewer, at
// 48^2: as the volume (an empty 32^3 frame whose TF is the medium everywhere:
// its box is [-15.5, 15.5]^3) or as a mesh box of the same extent in a
// transparent frame.
Scene dense_box_scene(bool as_mesh);

// Means of two renders of the dense box over its interior pixels (opaque in
// `volume` with all neighbours 2 px around), and their rms difference.
struct BoxComparison {
  float mean_mesh = 0.0f, mean_volume = 0.0f;
  float rms_difference = 0.0f;  // stripes and any other per-pixel disagreement
};
BoxComparison compare_box(const Image& mesh, const Image& volume);

}  // namespace penumbra::testing

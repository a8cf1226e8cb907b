#pragma once
// Procedural volumes with analytic values, for tests, benchmarks and the demo
// when no data files are present. Every generator writes float32 values in
// [0, 1] on a grid of the requested size with spacing 1, centred at the origin.
// Positions are given in normalised coordinates p in [-1, 1]^3 with
// p = 2 i / (n - 1) - 1 per axis.
//
//   spheres         three spheres with a linear radial profile
//                   v = max_k clamp(1 - |p - c_k| / r_k, 0, 1); the iso-surface
//                   v = s of sphere k has radius r_k (1 - s) (see kSpheres).
//   marschner-lobb  Marschner & Lobb (1994) test signal, f_M = 6, alpha = 0.25.
//   slab            constant 1 everywhere: a homogeneous medium filling the
//                   box, so transmittance along a chord of length d is
//                   exp(-sigma_t d).
//   edge            a sharp half-plane occluder: v = 1 for x < 0 and
//                   z in [0.2, 0.4], else 0 (a receiver is a scene floor plane).
//   chirp           a thin layer z in [0.2, 0.4] whose value is a chirp along x:
//                   v = 0.5 + 0.5 cos(2 pi phi(x)), with the local frequency
//                   rising linearly from 1 to n/8 cycles per box width.
//   shell           translucent shell (v = 0.5 for r in [0.55, 0.85]) around an
//                   opaque core (v = 1 for r < 0.35), centred.
//   empty           v = 0: a scene made only of meshes still has a volume,
//                   whose box and spacing set the camera and the TF unit length.
#include "penumbra/base/math.h"
#include "penumbra/volume/volume.h"

#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace penumbra {

struct ProceduralSphere {
  vec3 center;   // normalised coordinates
  float radius;  // normalised units (fraction of the half box edge)
};
inline constexpr ProceduralSphere kSpheres[3] = {
    {vec3(-0.35f, -0.2f, 0.05f), 0.38f},
    {vec3(0.38f, 0.12f, 0.1f), 0.32f},
    {vec3(0.0f, 0.45f, -0.35f), 0.26f},
};

struct ProceduralInfo {
  std::string name;
  std::string doc;
};

// The generators' names with one-line docs.
const std::vector<ProceduralInfo>& procedural_volumes();

// Default size when a scene gives none.
inline constexpr int kDefaultProceduralSize = 64;

// Throws InvalidArgument naming "builtin" for an unknown name and "size" for
// dimensions below 2 (and OutOfMemoryBudget for huge ones).
std::shared_ptr<Volume> make_procedural_volume(std::string_view name, ivec3 size);

// The analytic field of a generator at a normalised position (what the voxels
// sample), for tests.
float procedural_value(std::string_view name, vec3 p, ivec3 size);

}  // namespace penumbra

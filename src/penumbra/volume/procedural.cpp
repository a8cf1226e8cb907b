#include "penumbra/volume/procedural.h"

#include "penumbra/base/error.h"
#include "penumbra/base/parallel.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace penumbra {
namespace {

float spheres(vec3 p, ivec3) {
  float v = 0.0f;
  for (const ProceduralSphere& s : kSpheres) v = std::max(v, clamp01(1.0f - glm::length(p - s.center) / s.radius));
  return v;
}

float marschner_lobb(vec3 p, ivec3) {
  constexpr float kFrequency = 6.0f;
  constexpr float kAlpha = 0.25f;
  const float r = std::sqrt(p.x * p.x + p.y * p.y);
  const float rho_r = std::cos(2.0f * kPi * kFrequency * std::cos(kPi * r / 2.0f));
  return (1.0f - std::sin(kPi * p.z / 2.0f) + kAlpha * (1.0f + rho_r)) / (2.0f * (1.0f + kAlpha));
}

float slab(vec3, ivec3) { return 1.0f; }

float empty(vec3, ivec3) { return 0.0f; }

float edge(vec3 p, ivec3) { return (p.x < 0.0f && p.z >= 0.2f && p.z <= 0.4f) ? 1.0f : 0.0f; }

float chirp(vec3 p, ivec3 size) {
  if (p.z < 0.2f || p.z > 0.4f) return 0.0f;
  // Local frequency f(u) = f0 + (f1 - f0) u cycles per box width, u in [0, 1];
  // the phase is its integral over the box width.
  const float f0 = 1.0f;
  const float f1 = std::max(2.0f, float(size.x) / 8.0f);
  const float u = 0.5f * (p.x + 1.0f);
  const float phase = f0 * u + 0.5f * (f1 - f0) * u * u;
  return 0.5f + 0.5f * std::cos(2.0f * kPi * phase);
}

float shell(vec3 p, ivec3) {
  const float r = glm::length(p);
  if (r < 0.35f) return 1.0f;
  if (r >= 0.55f && r <= 0.85f) return 0.5f;
  return 0.0f;
}

using Field = float (*)(vec3, ivec3);

struct Generator {
  const char* name;
  Field field;
};
constexpr Generator kGenerators[] = {
    {"spheres", spheres}, {"marschner-lobb", marschner_lobb}, {"slab", slab},
    {"edge", edge},       {"chirp", chirp},                   {"shell", shell},
    {"empty", empty},
};

Field find_field(std::string_view name) {
  for (const Generator& g : kGenerators) {
    if (name == g.name) return g.field;
  }
  std::string known;
  for (const Generator& g : kGenerators) known += fmt::format("{}{}", known.empty() ? "" : ", ", g.name);
  throw InvalidArgument("builtin", fmt::format("unknown procedural volume '{}' (known: {})", name, known));
}

}  // namespace

const std::vector<ProceduralInfo>& procedural_volumes() {
  static const std::vector<ProceduralInfo> list = {
      {"spheres", "three spheres with a linear radial profile (iso-value s -> radius r (1 - s))"},
      {"marschner-lobb", "Marschner-Lobb test signal, f_M = 6, alpha = 0.25"},
      {"slab", "homogeneous medium (value 1) filling the box: transmittance exp(-sigma_t d)"},
      {"edge", "sharp half-plane occluder (x < 0, 0.2 <= z <= 0.4), for penumbra tests"},
      {"chirp", "layer at 0.2 <= z <= 0.4 whose value is a chirp along x, for shadow filter tests"},
      {"shell", "translucent shell (value 0.5) around an opaque core (value 1)"},
      {"empty", "zero everywhere: the frame of a scene made only of meshes (its box places the camera)"},
  };
  return list;
}

float procedural_value(std::string_view name, vec3 p, ivec3 size) { return find_field(name)(p, size); }

std::shared_ptr<Volume> make_procedural_volume(std::string_view name, ivec3 size) {
  const Field field = find_field(name);
  if (size.x < 2 || size.y < 2 || size.z < 2) {
    throw InvalidArgument("size", fmt::format("procedural volumes need at least 2 voxels per axis, got {}x{}x{}",
                                              size.x, size.y, size.z));
  }
  auto volume = std::make_shared<Volume>(size, VoxelType::Float32);
  float* voxels = volume->frame_as<float>(0);
  const vec3 to_normalized = 2.0f / vec3(size - 1);
  parallel_for(0, size.z, [&](std::int64_t z0, std::int64_t z1) {
    for (int z = int(z0); z < int(z1); ++z) {
      for (int y = 0; y < size.y; ++y) {
        for (int x = 0; x < size.x; ++x) {
          const vec3 p = vec3(x, y, z) * to_normalized - 1.0f;
          voxels[x + std::int64_t(size.x) * (y + std::int64_t(size.y) * z)] = field(p, size);
        }
      }
    }
  });
  volume->set_source(fmt::format("builtin:{} {}x{}x{}", name, size.x, size.y, size.z));
  return volume;
}

}  // namespace penumbra

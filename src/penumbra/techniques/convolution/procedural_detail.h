#pragma once
// Volumetric detail functions for the mesh interiors of Patel et al. 2013,
// section 4 (not yet wired to a renderer: meshes come in a later pass):
//   improved noise   K. Perlin, "Improving Noise", SIGGRAPH 2002: gradient
//                    noise with the quintic fade 6t^5 - 15t^4 + 10t^3 and the 12
//                    cube-edge gradients; zero at every lattice point. The
//                    permutation is a fixed shuffle of 0..255 (any permutation
//                    is a valid instance of the definition);
//   fBm              sum_i gain^i noise(lacunarity^i p), i < octaves;
//   ridged           Musgrave's ridged multifractal: signal_i =
//                    (offset - |noise|)^2 weighted by the previous octave's
//                    signal (clamped to [0, 1]) times gain, octave amplitudes
//                    lacunarity^(-i H) with H = 1;
// each optionally time dependent through a fourth coordinate folded into z
// (p.z + time * 1.7: a moving slice of the 3D field, cheaper than 4D noise).
#include "penumbra/base/math.h"

#include <array>
#include <cstdint>

namespace penumbra {

struct NoiseTable {
  std::array<std::uint8_t, 512> perm{};  // the permutation, repeated twice
};

NoiseTable make_noise_table(std::uint64_t seed = 0);

PENUMBRA_HD inline float noise_fade(float t) { return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f); }

PENUMBRA_HD inline float noise_grad(int hash, float x, float y, float z) {
  const int h = hash & 15;
  const float u = h < 8 ? x : y;
  const float v = h < 4 ? y : (h == 12 || h == 14 ? x : z);
  return ((h & 1) ? -u : u) + ((h & 2) ? -v : v);
}

PENUMBRA_HD inline float improved_noise(const NoiseTable& t, vec3 p) {
  const vec3 f = glm::floor(p);
  const int X = int(f.x) & 255, Y = int(f.y) & 255, Z = int(f.z) & 255;
  const float x = p.x - f.x, y = p.y - f.y, z = p.z - f.z;
  const float u = noise_fade(x), v = noise_fade(y), w = noise_fade(z);
  const auto& P = t.perm;
  const int A = P[X] + Y, AA = P[A] + Z, AB = P[A + 1] + Z;
  const int B = P[X + 1] + Y, BA = P[B] + Z, BB = P[B + 1] + Z;
  return glm::mix(glm::mix(glm::mix(noise_grad(P[AA], x, y, z), noise_grad(P[BA], x - 1, y, z), u),
                           glm::mix(noise_grad(P[AB], x, y - 1, z), noise_grad(P[BB], x - 1, y - 1, z), u), v),
                  glm::mix(glm::mix(noise_grad(P[AA + 1], x, y, z - 1), noise_grad(P[BA + 1], x - 1, y, z - 1), u),
                           glm::mix(noise_grad(P[AB + 1], x, y - 1, z - 1),
                                    noise_grad(P[BB + 1], x - 1, y - 1, z - 1), u),
                           v),
                  w);
}

struct FractalParams {
  int octaves = 5;
  float lacunarity = 2.0f;
  float gain = 0.5f;
  float offset = 1.0f;  // ridged only
  float time = 0.0f;
};

PENUMBRA_HD inline vec3 noise_at_time(vec3 p, float time) { return vec3(p.x, p.y, p.z + 1.7f * time); }

PENUMBRA_HD inline float fbm(const NoiseTable& t, vec3 p, const FractalParams& f) {
  p = noise_at_time(p, f.time);
  float sum = 0.0f, amplitude = 1.0f;
  for (int i = 0; i < f.octaves; ++i) {
    sum += amplitude * improved_noise(t, p);
    p *= f.lacunarity;
    amplitude *= f.gain;
  }
  return sum;
}

PENUMBRA_HD inline float ridged_multifractal(const NoiseTable& t, vec3 p, const FractalParams& f) {
  p = noise_at_time(p, f.time);
  float sum = 0.0f, weight = 1.0f, frequency_weight = 1.0f;
  for (int i = 0; i < f.octaves; ++i) {
    float signal = f.offset - glm::abs(improved_noise(t, p));
    signal *= signal * weight;
    weight = glm::clamp(signal * f.gain, 0.0f, 1.0f);
    sum += signal * frequency_weight;
    frequency_weight /= f.lacunarity;  // H = 1
    p *= f.lacunarity;
  }
  return sum;
}

}  // namespace penumbra

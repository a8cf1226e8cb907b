#pragma once
// Volumetric detail functions for the mesh interiors of Patel et al. 2013,
// section 4, evaluated for a mesh through DetailView (detail_view.h):
//   improved noise   K. Perlin, "Improving Noise", SIGGRAPH 2002: gradient
//                    noise with the quintic fade 6t^5 - 15t^4 + 10t^3 and the 12
//                    cube-edge gradients; zero at every lattice point. The
//                    permutation is a seeded shuffle of 0..255 (any permutation
//                    is a valid instance of the definition);
//   fBm              sum_i gain^i noise(lacunarity^i p), i < octaves;
//   ridged           Musgrave's ridged multifractal: signal_i =
//                    (offset - |noise|)^2 weighted by the previous octave's
//                    signal (clamped to [0, 1]) times gain, octave amplitudes
//                    lacunarity^(-i H) with H = 1;
// each in 3D, or in 4D with time as the fourth coordinate (all four scaled by
// the lacunarity per octave, so finer octaves also change faster). The 4D
// noise is the same construction one dimension up: quintic fade per axis,
// quadrilinear blend of the 16 corner ramps, and 32 gradients on the edges of
// the 4D hypercube (one component 0, the others +-1), picked by hash & 31 from
// the nested permutation P[P[P[P[x] + y] + z] + w]. |noise4| <= 3 (each
// ramp's |g . d| is at most 3 inside its cell and the weights sum to one).
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

// The gradient of hash & 31: component (hash & 31) >> 3 is zero, the low three
// bits are the signs of the other three.
PENUMBRA_HD inline float noise_grad(int hash, float x, float y, float z, float w) {
  const int h = hash & 31;
  const int zero = h >> 3;
  const float a = zero == 0 ? y : x;
  const float b = zero <= 1 ? z : y;
  const float c = zero <= 2 ? w : z;
  return ((h & 1) ? -a : a) + ((h & 2) ? -b : b) + ((h & 4) ? -c : c);
}

PENUMBRA_HD inline float improved_noise(const NoiseTable& t, vec4 p) {
  const vec4 f = glm::floor(p);
  const int X = int(f.x) & 255, Y = int(f.y) & 255, Z = int(f.z) & 255, W = int(f.w) & 255;
  const vec4 d = p - f;  // position in the cell, [0, 1)^4
  const auto& P = t.perm;
  // Corner c has offsets (c & 1, c >> 1 & 1, c >> 2 & 1, c >> 3); indices stay
  // below 512 because every partial hash is at most 255 + 256.
  float ramp[16];
  for (int c = 0; c < 16; ++c) {
    const int ox = c & 1, oy = (c >> 1) & 1, oz = (c >> 2) & 1, ow = c >> 3;
    const int hash = P[P[P[P[X + ox] + Y + oy] + Z + oz] + W + ow];
    ramp[c] = noise_grad(hash, d.x - float(ox), d.y - float(oy), d.z - float(oz), d.w - float(ow));
  }
  // Blend along x, then y, z and w (pairs differ in the lowest remaining bit).
  const float u[4] = {noise_fade(d.x), noise_fade(d.y), noise_fade(d.z), noise_fade(d.w)};
  for (int axis = 0, count = 16; axis < 4; ++axis, count /= 2)
    for (int k = 0; k < count / 2; ++k) ramp[k] = glm::mix(ramp[2 * k], ramp[2 * k + 1], u[axis]);
  return ramp[0];
}

struct FractalParams {
  int octaves = 5;
  float lacunarity = 2.0f;
  float gain = 0.5f;
  float offset = 1.0f;  // ridged only
  float time = 0.0f;    // the fourth noise coordinate when the detail is time dependent
};

namespace noise_detail {

// One implementation for the 3D and 4D forms (V = vec3 or vec4).
template <class V> PENUMBRA_HD float fbm(const NoiseTable& t, V p, const FractalParams& f) {
  float sum = 0.0f, amplitude = 1.0f;
  for (int i = 0; i < f.octaves; ++i) {
    sum += amplitude * improved_noise(t, p);
    p *= f.lacunarity;
    amplitude *= f.gain;
  }
  return sum;
}

template <class V> PENUMBRA_HD float ridged(const NoiseTable& t, V p, const FractalParams& f) {
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

}  // namespace noise_detail

// 3D forms: f.time is not used. 4D forms: p.w is the time coordinate (callers
// pass f.time there, see DetailView).
PENUMBRA_HD inline float fbm(const NoiseTable& t, vec3 p, const FractalParams& f) {
  return noise_detail::fbm(t, p, f);
}
PENUMBRA_HD inline float fbm(const NoiseTable& t, vec4 p, const FractalParams& f) {
  return noise_detail::fbm(t, p, f);
}
PENUMBRA_HD inline float ridged_multifractal(const NoiseTable& t, vec3 p, const FractalParams& f) {
  return noise_detail::ridged(t, p, f);
}
PENUMBRA_HD inline float ridged_multifractal(const NoiseTable& t, vec4 p, const FractalParams& f) {
  return noise_detail::ridged(t, p, f);
}

}  // namespace penumbra

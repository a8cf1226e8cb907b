#pragma once
// Area-light transmittance for shadow-rays' `light_samples` option: the
// light's visibility from a point as the weighted mean transmittance of n
// shadow rays toward points of the light,
//   V(x) = sum_k w_k T(x -> y_k) / sum_k w_k,
// with the directions y_k drawn by sample_light_direction (the path tracer's
// light sampling, scene/light_sampling.h: uniform over a distant light's cone,
// Gaussian on its virtual light plane, uniform in a sphere's solid angle,
// uniform over a disk's area) and w_k its weight (radiance / pdf; constant
// except for disks, whose cosine and 1/r^2 vary over the disk).
//
// The n numbers in [0,1)^2 are a Fibonacci lattice ((k + 1/2) / n,
// frac(k / golden ratio)), stratified for every n, shifted modulo 1 by a hash
// of the point's coordinates (quantised to 1/64 world unit, so that the
// scalar and packet paths' last-bit differences in a sample's position do
// not change its shift) and the light index (a Cranley-Patterson rotation):
// deterministic, the same image on every run and backend, and noise (not n
// overlapping copies of a hard shadow) where n is small.
//
// Written once over the lane type: a packet marches its lanes' k-th shadow
// rays together (march_transmittance<L>).
#include "penumbra/base/rng.h"
#include "penumbra/render/march.h"
#include "penumbra/scene/light_sampling.h"

namespace penumbra {

// Whether a light has an extent that light samples resolve (otherwise every
// sample is its centre).
PENUMBRA_HD inline bool light_has_extent(const Light& light) {
  switch (light.type) {
    case LightType::Distant: return light.angle_deg > 0.0f || light.spread_y_deg() > 0.0f;
    case LightType::Sphere:
    case LightType::Disk: return light.radius > 0.0f;
    default: return false;
  }
}

// Point k of the n-point lattice shifted by `shift` (modulo 1).
PENUMBRA_HD inline vec2 light_lattice_point(int k, int n, vec2 shift) {
  const float inverse_golden = 0.61803398875f;
  const vec2 u(((float(k) + 0.5f) / float(n)) + shift.x, float(k) * inverse_golden + shift.y);
  return glm::min(u - glm::floor(u), vec2(0.99999994f));
}

// The lattice shift of a point: a hash of its quantised coordinates and the
// light.
PENUMBRA_HD inline vec2 light_lattice_shift(vec3 p, int light) {
  const vec3 q = glm::floor(glm::clamp(p * 64.0f, vec3(-2.0e9f), vec3(2.0e9f)));
  // (NaN, as in a packet's unused lane, hashes as 0.)
  const auto bits = [](float x) { return std::uint64_t(std::uint32_t(std::int32_t(x == x ? x : 0.0f))); };
  std::uint64_t h = mix_bits(bits(q.x) | (bits(q.y) << 32));
  h = mix_bits(h ^ (bits(q.z) | (std::uint64_t(std::uint32_t(light)) << 32)));
  const float scale = 1.0f / 16777216.0f;  // 24-bit fractions
  return vec2(float(h >> 40) * scale, float((h >> 16) & 0xffffffu) * scale);
}

// The weighted mean above for the lanes of `points`, with T the given
// transmittance(const Ray* rays, const float* distances) of one shadow ray
// per lane (L::Float, or L::Vec3 per colour channel).
template <class L, class Transmittance>
PENUMBRA_HD auto area_light_mean(const Light& light, int light_index, const vec3* points, int samples,
                                 const Transmittance& transmittance) {
  using F = typename L::Float;
  using T = decltype(transmittance(static_cast<const Ray*>(nullptr), static_cast<const float*>(nullptr)));
  constexpr int W = L::kWidth;
  vec2 shifts[W];
  for (int i = 0; i < W; ++i) shifts[i] = light_lattice_shift(points[i], light_index);
  T sum(0.0f);
  F weights(0.0f);
  for (int k = 0; k < samples; ++k) {
    Ray rays[W];
    float distances[W], w[W];
    for (int i = 0; i < W; ++i) {
      const LightDirectionSample s =
          sample_light_direction(light, points[i], light_lattice_point(k, samples, shifts[i]));
      rays[i] = Ray{points[i], s.to_light};
      distances[i] = s.distance;
      w[i] = s.weight.x + s.weight.y + s.weight.z;  // the colour is the same for every sample
    }
    const F weight = L::load(w);
    sum += weight * transmittance(rays, distances);
    weights += weight;
  }
  return select(weights > 0.0f, sum / max(weights, F(1e-30f)), T(1.0f));
}

// V(x) above through the volume, for the lanes of `points` that are on in
// `active`.
template <class L, class Sampler>
PENUMBRA_HD typename L::Float area_light_transmittance(const RenderView& v, const Sampler& sampler,
                                                       const Light& light, int light_index, const vec3* points,
                                                       int samples, float density_scale, typename L::Mask active,
                                                       RayStats& stats) {
  return area_light_mean<L>(light, light_index, points, samples, [&](const Ray* rays, const float* distances) {
    return march_transmittance<L>(v, sampler, rays, distances, density_scale, active, stats);
  });
}

}  // namespace penumbra

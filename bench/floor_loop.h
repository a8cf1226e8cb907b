#pragma once
// The floor loops of bench_march: the least a ray caster does per sample on
// the same kernels as the shared loop (trilinear uint8 sample, TF table,
// opacity correction, front-to-back compositing, early termination) with no
// empty-space skipping, no clip planes and no lighting, written once over
// the lane type like march_rays. Stages stop after sampling (Sample), after
// the extinction lookup (Extinction) or composite fully (Composite), so the
// differences between them say what each part costs.
#include "penumbra/base/lanes.h"
#include "penumbra/render/march.h"
#include "penumbra/volume/volume_sampler.h"

#include <cstdint>

namespace penumbra::bench {

enum class FloorStage { Sample, Extinction, Composite };

template <class L, FloorStage Stage>
PENUMBRA_HD PENUMBRA_FORCE_INLINE void floor_rays(const RenderView& v, const VolumeSampler<std::uint8_t>& sampler,
                                                  const Ray* rays, vec4* out, std::uint64_t& samples) {
  using F = typename L::Float;
  using I = typename L::Int;
  using V = typename L::Vec3;
  constexpr int W = L::kWidth;
  vec3 origins[W], directions[W];
  float t0[W], t1[W];
  std::int32_t counts[W];
  int most = 0;
  for (int i = 0; i < W; ++i) {
    const Interval iv = intersect_box(rays[i], v.box, 0.0f, kInfinity);
    origins[i] = v.volume.index_from_world(rays[i].origin);
    directions[i] = rays[i].direction / v.volume.spacing;
    t0[i] = iv.t0;
    t1[i] = iv.t1;
    counts[i] = iv.empty() ? 0 : int(glm::ceil((iv.t1 - iv.t0) / v.step));
    most = counts[i] > most ? counts[i] : most;
  }
  const V o = pack_lanes<L>(origins), d = pack_lanes<L>(directions);
  const F first = L::load(t0), last = L::load(t1);
  const I count = L::load(counts);
  const TransferFunctionView tf = v.tf;
  const float min_transmittance = 1.0f - v.ert_threshold;
  V color(0.0f);
  F transmittance(1.0f), sum(0.0f);
  auto alive = I(0) < count;
  std::uint64_t taken = 0;
  for (int k = 0; k < most && any(alive); ++k) {
    alive = alive & (I(k) < count);
    const F start = first + float(k) * v.step;
    const F length = min(F(v.step), last - start);
    const F t = start + 0.5f * length;
    const F value = sampler.sample<L>(o + t * d);
    taken += std::uint64_t(count_true(alive));
    if constexpr (Stage == FloorStage::Sample) {
      sum += select(alive, value, F(0.0f));
      continue;
    }
    const auto at = tf.locate<L>(value);
    const F sigma_t = tf.sigma_t<L>(at);
    if constexpr (Stage == FloorStage::Extinction) {
      sum += select(alive, sigma_t, F(0.0f));
      continue;
    }
    const auto lit = alive & (sigma_t > 0.0f);
    if (none(lit)) continue;
    const F alpha = 1.0f - exp_nonpositive(-sigma_t * length);
    color += select(lit, (transmittance * alpha) * tf.color<L>(at), V(0.0f));
    transmittance = select(lit, transmittance * (1.0f - alpha), transmittance);
    alive = alive & !(lit & (transmittance <= min_transmittance));
  }
  samples += taken;
  vec3 c[W];
  unpack_lanes<L>(color + V(sum), c);
  float tr[W];
  L::store(transmittance, tr);
  for (int i = 0; i < W; ++i) out[i] = vec4(c[i], 1.0f - tr[i]);
}

// A whole image of floor rays, single-threaded, in blocks of 4 x (W / 4)
// pixels as the packet path takes them. Returns the samples taken.
template <class L, FloorStage Stage>
std::uint64_t floor_image(const RenderView& v, vec4* pixels) {
  constexpr int W = L::kWidth;
  constexpr int bw = W < 4 ? 1 : 4, bh = W / bw;
  const VolumeSampler<std::uint8_t> sampler(v.volume.data, v.volume.dims);
  std::uint64_t samples = 0;
  for (int by = 0; by < v.height; by += bh) {
    for (int bx = 0; bx < v.width; bx += bw) {
      Ray rays[W];
      for (int i = 0; i < W; ++i) {
        const int x = glm::min(bx + i % bw, v.width - 1), y = glm::min(by + i / bw, v.height - 1);
        rays[i] = v.camera.pixel_ray(float(x) + 0.5f, float(y) + 0.5f, v.width, v.height);
      }
      vec4 out[W];
      floor_rays<L, Stage>(v, sampler, rays, out, samples);
      for (int i = 0; i < W; ++i) {
        const int x = bx + i % bw, y = by + i / bw;
        if (x < v.width && y < v.height) pixels[std::int64_t(y) * v.width + x] = out[i];
      }
    }
  }
  return samples;
}

// Entry points of the SIMD units (floor_loop_simd.cpp), by stage.
namespace N_AVX2 {
std::uint64_t floor_image_simd(const RenderView& v, vec4* pixels, FloorStage stage);
}
namespace N_AVX3 {
std::uint64_t floor_image_simd(const RenderView& v, vec4* pixels, FloorStage stage);
}

}  // namespace penumbra::bench

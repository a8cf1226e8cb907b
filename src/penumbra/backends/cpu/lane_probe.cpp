// SIMD unit (cmake/PenumbraSimd.cmake), test support: see lane_probe.h.
#include "penumbra/backends/cpu/lane_probe.h"

#include "penumbra/backends/cpu/simd_lanes.h"
#include "penumbra/render/lighting.h"
#include "penumbra/volume/volume_sampler.h"

namespace penumbra {
namespace HWY_NAMESPACE {

__attribute__((flatten)) void run_lane_probe(const LaneProbe& probe) {
  using L = SimdLanes;
  using F = L::Float;
  using V = L::Vec3;
  constexpr int W = L::kWidth;
  if (probe.gathered) {
    for (int first = 0; first + W <= probe.count; first += W) {
      F c[4];
      gather4(probe.table, L::load(probe.table_indices + first), c[0], c[1], c[2], c[3]);
      float lanes[4][W];
      for (int k = 0; k < 4; ++k) L::store(c[k], lanes[k]);
      for (int i = 0; i < W; ++i) probe.gathered[first + i] = vec4(lanes[0][i], lanes[1][i], lanes[2][i], lanes[3][i]);
    }
  }
  if (!probe.view) return;
  const RenderView& v = *probe.view;
  const AnyVoxelSampler sampler(v.volume.data, v.volume.dims, v.volume.type);
  for (int first = 0; first + W <= probe.count; first += W) {
    const V p = pack_lanes<L>(probe.positions + first);
    const F value = sampler.sample<L>(p);
    L::store(value, probe.values + first);
    vec3 out[W];
    unpack_lanes<L>(sampler.gradient<L>(p), out);
    for (int i = 0; i < W; ++i) probe.gradients[first + i] = out[i];
    if (v.normals.texels) {
      unpack_lanes<L>(v.normals.sample<L>(p), out);
      for (int i = 0; i < W; ++i) probe.normals[first + i] = out[i];
    }
    TransferFunctionView::Place<L> at;
    const F sigma = sample_extinction<L>(v.tf, sampler, value, at);
    float s[W];
    L::store(sigma, s);
    unpack_lanes<L>(v.tf.color<L>(at), out);
    for (int i = 0; i < W; ++i) probe.tf[first + i] = vec4(out[i], s[i]);
    const F x = L::load(probe.numbers + first);
    if (probe.others) {
      const F y = L::load(probe.others + first);
      float lo[W], hi[W], c[W];
      L::store(min(x, y), lo);
      L::store(max(x, y), hi);
      L::store(clamp(x, F(-1.0f), F(1.0f)), c);
      for (int i = 0; i < W; ++i) probe.min_max_clamp[first + i] = vec3(lo[i], hi[i], c[i]);
    }
    float e[W], l[W], w[W];
    L::store(exp_nonpositive(-x), e);
    L::store(log_positive(x), l);
    L::store(pow_unit(x / (1.0f + x), 7.5f), w);
    for (int i = 0; i < W; ++i) probe.exp_log_pow[first + i] = vec3(e[i], l[i], w[i]);
    const V world = V(v.volume.origin) + p * V(v.volume.spacing);
    const LightSampleL<L> ls = sample_light<L>(v.lights[0], world);
    unpack_lanes<L>(ls.to_light, out);
    for (int i = 0; i < W; ++i) probe.to_light[first + i] = out[i];
    Ray rays[W];
    float distances[W];
    vec3 origins[W], directions[W];
    unpack_lanes<L>(world, origins);
    unpack_lanes<L>(ls.to_light, directions);
    L::store(ls.distance, distances);
    for (int i = 0; i < W; ++i) rays[i] = Ray{origins[i], directions[i]};
    RayStats stats;
    L::store(march_transmittance<L>(v, sampler, rays, distances, 1.0f, L::Mask(true), stats),
             probe.transmittance + first);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace penumbra

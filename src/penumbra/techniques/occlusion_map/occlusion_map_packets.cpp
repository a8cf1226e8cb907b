// SIMD unit (cmake/PenumbraSimd.cmake): occlusion-map's soft-shadow marches,
// 8 or 16 at a time (soft_shadow_batch.h), DVR mode's AO grid nodes, and
// DVR mode's samples as packets
// of the shared loop (occlusion_shading.h). Everything here is inlined into
// the flatten functions or named after this unit's target (see
// backends/cpu/packet_render.h on why).
#include "penumbra/backends/cpu/packet_render.h"
#include "penumbra/backends/cpu/simd_lanes.h"
#include "penumbra/techniques/occlusion_map/occlusion_shading.h"
#include "penumbra/techniques/occlusion_map/soft_shadow_batch.h"

namespace penumbra {
namespace HWY_NAMESPACE {

__attribute__((flatten)) void march_batch(const OcclusionQueries<2>& queries, float t, const SoftShadowQueries& batch,
                                          float* out) {
  using L = SimdLanes;
  using Q = SoftShadowQueries;
  static_assert(SoftShadowBatch::kMaxWidth % L::kWidth == 0, "batches are padded to whole packets");
  const auto load3 = [&](int f, int i) {
    return Vec3V(L::load(batch.field(f) + i), L::load(batch.field(f + 1) + i), L::load(batch.field(f + 2) + i));
  };
  for (int i = 0; i < batch.count; i += L::kWidth) {
    const FloatV visible = queries.soft_shadow_lanes<L>(
        load3(Q::Px, i), load3(Q::Nx, i), load3(Q::Lx, i), L::load(batch.field(Q::Distance) + i),
        L::load(batch.field(Q::Spread) + i), t, L::load(batch.field(Q::Own) + i), MaskV(true));
    L::store(visible, out + i);
  }
}

__attribute__((flatten)) void ambient_batch(const OcclusionQueries<2>& queries, ValueNormalisation normalise,
                                             const VolumeView& volume, const float* const xyz[3], int count,
                                             float* out) {
  using L = SimdLanes;
  const AnyVoxelSampler sampler(volume.data, volume.dims, volume.type);
  for (int i = 0; i < count; i += L::kWidth) {
    const Vec3V world(L::load(xyz[0] + i), L::load(xyz[1] + i), L::load(xyz[2] + i));
    const Vec3V index = volume.index_from_world<L>(world);
    const FloatV value = sampler.sample<L>(index);
    L::store(dvr_ambient<L>(queries, normalise, volume, sampler, index, world, value, MaskV(true), kDvrGridNode),
             out + i);
  }
}

}  // namespace HWY_NAMESPACE

template <SimdTarget Target>
void dvr_ambient_batch(const OcclusionQueries<2>& queries, ValueNormalisation normalise, const VolumeView& volume,
                       const float* const xyz[3], int count, float* out) {
  static_assert(Target == HWY_NAMESPACE::kThisSimdTarget, "each SIMD unit instantiates its own target only");
  HWY_NAMESPACE::ambient_batch(queries, normalise, volume, xyz, count, out);
}

template void dvr_ambient_batch<SimdTarget::PENUMBRA_SIMD_TARGET>(const OcclusionQueries<2>&, ValueNormalisation,
                                                                  const VolumeView&, const float* const[3], int,
                                                                  float*);

template <SimdTarget Target>
void march_soft_shadows(const OcclusionQueries<2>& queries, float t, const SoftShadowQueries& batch, float* out) {
  static_assert(Target == HWY_NAMESPACE::kThisSimdTarget, "each SIMD unit instantiates its own target only");
  HWY_NAMESPACE::march_batch(queries, t, batch, out);
}

template void march_soft_shadows<SimdTarget::PENUMBRA_SIMD_TARGET>(const OcclusionQueries<2>&, float,
                                                                     const SoftShadowQueries&, float*);

}  // namespace penumbra

PENUMBRA_INSTANTIATE_PACKETS(DvrOcclusionLighting<2, AnyVoxelSampler>);

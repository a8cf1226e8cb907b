// SIMD unit (cmake/PenumbraSimd.cmake): occlusion-map's soft-shadow marches,
// 8 or 16 at a time (soft_shadow_batch.h), and DVR mode's samples as packets
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

}  // namespace HWY_NAMESPACE

template <SimdTarget Target>
void march_soft_shadows(const OcclusionQueries<2>& queries, float t, const SoftShadowQueries& batch, float* out) {
  static_assert(Target == HWY_NAMESPACE::kThisSimdTarget, "each SIMD unit instantiates its own target only");
  HWY_NAMESPACE::march_batch(queries, t, batch, out);
}

template void march_soft_shadows<SimdTarget::PENUMBRA_SIMD_TARGET>(const OcclusionQueries<2>&, float,
                                                                     const SoftShadowQueries&, float*);

}  // namespace penumbra

PENUMBRA_INSTANTIATE_PACKETS(DvrOcclusionLighting<2, AnyVoxelSampler>);

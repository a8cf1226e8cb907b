// SIMD unit (cmake/PenumbraSimd.cmake): ipsvi's recorded light segments
// (segment_tape.h), 8 or 16 at a time, for either light model. Everything here is inlined into the
// flatten function or named after this unit's target (see
// backends/cpu/packet_render.h on why).
#include "penumbra/backends/cpu/simd_lanes.h"
#include "penumbra/techniques/ipsvi/segment_tape.h"

namespace penumbra {
namespace HWY_NAMESPACE {

template <bool Emission>
__attribute__((flatten)) void march_tape(const RenderView& shadow, const ForwardScattering& scattering,
                                         SegmentTape& tape) {
  using L = SimdLanes;
  constexpr int W = L::kWidth;
  static_assert(SegmentTape::kMaxWidth % W == 0 && SegmentTape::kCapacity % SegmentTape::kMaxWidth == 0,
                "tapes are padded to whole packets");
  const VolumeView& volume = shadow.volume;
  const AnyVoxelSampler sampler(volume.data, volume.dims, volume.type);
  const int n = tape.checkpoints;
  std::uint64_t samples = 0;
  for (int first = 0; first < tape.count; first += W) {
    Ray rays[W];
    float lengths[kMaxSegmentCheckpoints * W];
    for (int i = 0; i < W; ++i) {
      const int s = first + i;
      rays[i] = Ray{vec3(tape.from[0][s], tape.from[1][s], tape.from[2][s]),
                    vec3(tape.to_light[0][s], tape.to_light[1][s], tape.to_light[2][s])};
      for (int j = 0; j < n; ++j) lengths[j * W + i] = tape.lengths[j][s];
    }
    const int live = tape.count - first < W ? tape.count - first : W;
    const MaskV lanes = first_lanes<L>(live);
    OpticalDepthL<L> depth[kMaxSegmentCheckpoints];
    light_segment_depths_lanes<Emission, L>(shadow, sampler, rays, lengths, n, lanes, scattering, depth, samples);
    for (int j = 0; j < n; ++j) {
      L::store(depth[j].direct, tape.direct[j] + first);
      L::store(depth[j].diffuse.x, tape.diffuse[j][0] + first);
      L::store(depth[j].diffuse.y, tape.diffuse[j][1] + first);
      L::store(depth[j].diffuse.z, tape.diffuse[j][2] + first);
      if constexpr (Emission) {
        L::store(depth[j].emitted.x, tape.emitted[j][0] + first);
        L::store(depth[j].emitted.y, tape.emitted[j][1] + first);
        L::store(depth[j].emitted.z, tape.emitted[j][2] + first);
      }
    }
  }
  tape.samples += samples;
}

}  // namespace HWY_NAMESPACE

template <SimdTarget Target>
void march_segment_tape(const RenderView& shadow, const ForwardScattering& scattering, SegmentTape& tape) {
  static_assert(Target == HWY_NAMESPACE::kThisSimdTarget, "each SIMD unit instantiates its own target only");
  if (tape.emission) {
    HWY_NAMESPACE::march_tape<true>(shadow, scattering, tape);
  } else {
    HWY_NAMESPACE::march_tape<false>(shadow, scattering, tape);
  }
}

template void march_segment_tape<SimdTarget::PENUMBRA_SIMD_TARGET>(const RenderView&, const ForwardScattering&,
                                                                     SegmentTape&);

}  // namespace penumbra

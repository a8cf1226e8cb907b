// SIMD unit (cmake/PenumbraSimd.cmake): half-angle slicing's eye and light
// rows 8 or 16 pixels or texels at a time, the kernels of
// half_angle_kernels.h instantiated for SimdLanes. Everything here is inlined
// into the flatten functions or named after this unit's target (see
// backends/cpu/packet_render.h on why).
#include "penumbra/backends/cpu/simd_lanes.h"
#include "penumbra/techniques/half_angle/half_angle_kernels.h"

namespace penumbra {
namespace HWY_NAMESPACE {

__attribute__((flatten)) std::uint64_t eye_row(const HalfAngleKernel& k, const SlicedRows& eye, int slice,
                                               std::size_t first, int count) {
  const VolumeView& volume = k.view->volume;
  std::uint64_t samples = 0;
  eye_slice_row<SimdLanes>(k, AnyVoxelSampler(volume.data, volume.dims, volume.type), eye, slice, first, count,
                           samples);
  return samples;
}

__attribute__((flatten)) std::uint64_t light_row(const HalfAngleKernel& k, const SlicedRows& rays, int slice,
                                                 std::size_t first, int count, vec4* texels) {
  const VolumeView& volume = k.view->volume;
  std::uint64_t samples = 0;
  light_slice_row<SimdLanes>(k, AnyVoxelSampler(volume.data, volume.dims, volume.type), rays, slice, first, count,
                             texels, samples);
  return samples;
}

}  // namespace HWY_NAMESPACE

template <SimdTarget Target>
std::uint64_t eye_slice_row_packets(const HalfAngleKernel& k, const SlicedRows& eye, int slice, std::size_t first,
                                    int count) {
  static_assert(Target == HWY_NAMESPACE::kThisSimdTarget, "each SIMD unit instantiates its own target only");
  return HWY_NAMESPACE::eye_row(k, eye, slice, first, count);
}

template <SimdTarget Target>
std::uint64_t light_slice_row_packets(const HalfAngleKernel& k, const SlicedRows& rays, int slice, std::size_t first,
                                      int count, vec4* texels) {
  static_assert(Target == HWY_NAMESPACE::kThisSimdTarget, "each SIMD unit instantiates its own target only");
  return HWY_NAMESPACE::light_row(k, rays, slice, first, count, texels);
}

template std::uint64_t eye_slice_row_packets<SimdTarget::PENUMBRA_SIMD_TARGET>(const HalfAngleKernel&,
                                                                               const SlicedRows&, int, std::size_t,
                                                                               int);
template std::uint64_t light_slice_row_packets<SimdTarget::PENUMBRA_SIMD_TARGET>(const HalfAngleKernel&,
                                                                                 const SlicedRows&, int,
                                                                                 std::size_t, int, vec4*);

}  // namespace penumbra

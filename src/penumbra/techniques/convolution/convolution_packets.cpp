// SIMD unit (cmake/PenumbraSimd.cmake): convolution's carried light read 8
// or 16 pixels at a time (carried_light.h, read_carried_row), and the slab
// step of a light with several taps (light_propagation.h, convolve_row). Everything here
// is inlined into the flatten function or named after this unit's target (see
// backends/cpu/packet_render.h on why).
#include "penumbra/backends/cpu/simd_lanes.h"
#include "penumbra/techniques/convolution/carried_light.h"

namespace penumbra {
namespace HWY_NAMESPACE {

__attribute__((flatten)) std::uint64_t read_row(const CarriedReadView& r, int width, int y, std::size_t frame_plane,
                                                float* incoming, std::uint8_t* needs) {
  return read_carried_row<SimdLanes>(r, width, y, frame_plane, incoming, needs);
}

__attribute__((flatten)) void convolve_row_simd(const SlabFrame& f, const SlabMapping& m, const SlabKernel& k,
                                                const float* previous, int y, float* incoming) {
  convolve_row<SimdLanes>(f, m, k, previous, y, incoming);
}

}  // namespace HWY_NAMESPACE

template <SimdTarget Target>
std::uint64_t read_carried_row_packets(const CarriedReadView& r, int width, int y, std::size_t frame_plane,
                                       float* incoming, std::uint8_t* needs) {
  static_assert(Target == HWY_NAMESPACE::kThisSimdTarget, "each SIMD unit instantiates its own target only");
  return HWY_NAMESPACE::read_row(r, width, y, frame_plane, incoming, needs);
}

template std::uint64_t read_carried_row_packets<SimdTarget::PENUMBRA_SIMD_TARGET>(const CarriedReadView&, int, int,
                                                                                    std::size_t, float*,
                                                                                    std::uint8_t*);

template <SimdTarget Target>
void convolve_row_packets(const SlabFrame& f, const SlabMapping& m, const SlabKernel& k, const float* previous, int y,
                          float* incoming) {
  static_assert(Target == HWY_NAMESPACE::kThisSimdTarget, "each SIMD unit instantiates its own target only");
  HWY_NAMESPACE::convolve_row_simd(f, m, k, previous, y, incoming);
}

template void convolve_row_packets<SimdTarget::PENUMBRA_SIMD_TARGET>(const SlabFrame&, const SlabMapping&,
                                                                     const SlabKernel&, const float*, int, float*);

}  // namespace penumbra

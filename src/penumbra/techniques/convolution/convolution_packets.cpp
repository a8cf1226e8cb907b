// SIMD unit (cmake/PenumbraSimd.cmake): convolution's carried light read 8
// or 16 pixels at a time (carried_light.h, read_carried_row). Everything here
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

}  // namespace penumbra

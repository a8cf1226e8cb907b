// SIMD unit (cmake/PenumbraSimd.cmake): the floor loops as packets.
#include "floor_loop.h"

#include "penumbra/backends/cpu/simd_lanes.h"

namespace penumbra::bench::HWY_NAMESPACE {

__attribute__((flatten)) std::uint64_t floor_image_simd(const RenderView& v, vec4* pixels, FloorStage stage) {
  using L = penumbra::HWY_NAMESPACE::SimdLanes;
  switch (stage) {
    case FloorStage::Sample: return floor_image<L, FloorStage::Sample>(v, pixels);
    case FloorStage::Extinction: return floor_image<L, FloorStage::Extinction>(v, pixels);
    case FloorStage::Composite: break;
  }
  return floor_image<L, FloorStage::Composite>(v, pixels);
}

}  // namespace penumbra::bench::HWY_NAMESPACE

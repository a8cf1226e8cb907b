// SIMD unit (cmake/PenumbraSimd.cmake): the packet paths of the lightings
// the render layer itself declares (lighting.h).
#include "penumbra/backends/cpu/packet_render.h"
#include "penumbra/render/lighting.h"

PENUMBRA_INSTANTIATE_PACKETS(EmissionLighting);
PENUMBRA_INSTANTIATE_PACKETS(ScatteringLighting<NoShadows>);

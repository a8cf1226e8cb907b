// SIMD unit (cmake/PenumbraSimd.cmake): shadow-map's packet paths.
#include "penumbra/backends/cpu/packet_render.h"
#include "penumbra/techniques/shadow_map/shadow_map_kernels.h"

PENUMBRA_INSTANTIATE_PACKETS(ScatteringLighting<ShadowMapVisibility>);

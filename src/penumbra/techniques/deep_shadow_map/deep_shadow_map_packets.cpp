// SIMD unit (cmake/PenumbraSimd.cmake): deep-shadow-map's packet paths.
#include "penumbra/backends/cpu/packet_render.h"
#include "penumbra/techniques/deep_shadow_map/deep_shadow_map_kernels.h"

PENUMBRA_INSTANTIATE_PACKETS(ScatteringLighting<DeepShadowVisibility>);

// SIMD unit (cmake/PenumbraSimd.cmake): cssm's packet paths.
#include "penumbra/backends/cpu/packet_render.h"
#include "penumbra/techniques/cssm/cssm_kernels.h"

PENUMBRA_INSTANTIATE_PACKETS(ScatteringLighting<CssmVisibility>);

// SIMD unit (cmake/PenumbraSimd.cmake): cone-shadows's packet paths.
#include "penumbra/backends/cpu/packet_render.h"
#include "penumbra/techniques/cone_shadows/cone_march.h"

PENUMBRA_INSTANTIATE_PACKETS(ScatteringLighting<ConeMarch>);
PENUMBRA_INSTANTIATE_PACKETS(ScatteringLighting<CachedConeMarch>);

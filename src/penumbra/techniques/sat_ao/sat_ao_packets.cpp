// SIMD unit (cmake/PenumbraSimd.cmake): sat-ao's packet paths.
#include "penumbra/backends/cpu/packet_render.h"
#include "penumbra/techniques/sat_ao/ambient_occlusion.h"

PENUMBRA_INSTANTIATE_PACKETS(ScatteringLighting<AmbientOcclusion>);
PENUMBRA_INSTANTIATE_PACKETS(ScatteringLighting<CachedAmbientOcclusion>);

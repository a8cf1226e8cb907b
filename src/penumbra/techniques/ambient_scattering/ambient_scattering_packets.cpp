// SIMD unit (cmake/PenumbraSimd.cmake): ambient-scattering's packet paths.
#include "penumbra/backends/cpu/packet_render.h"
#include "penumbra/techniques/ambient_scattering/ambient_tube.h"

PENUMBRA_INSTANTIATE_PACKETS(ScatteringLighting<AmbientTube>);
PENUMBRA_INSTANTIATE_PACKETS(ScatteringLighting<CachedAmbientTube>);

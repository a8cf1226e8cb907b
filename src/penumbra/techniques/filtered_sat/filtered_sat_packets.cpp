// SIMD unit (cmake/PenumbraSimd.cmake): filtered-sat's packet paths.
#include "penumbra/backends/cpu/packet_render.h"
#include "penumbra/techniques/filtered_sat/filtered_visibility.h"

PENUMBRA_INSTANTIATE_PACKETS(ScatteringLighting<FilteredVisibility>);
PENUMBRA_INSTANTIATE_PACKETS(ScatteringLighting<CachedFilteredVisibility>);

// SIMD unit (cmake/PenumbraSimd.cmake): shadow-rays' packet paths.
#include "penumbra/backends/cpu/packet_render.h"
#include "penumbra/techniques/shadow_rays/shadow_ray_visibility.h"

PENUMBRA_INSTANTIATE_PACKETS(ScatteringLighting<ShadowRayVisibility>);
PENUMBRA_INSTANTIATE_PACKETS(ScatteringLighting<CachedShadowRayVisibility>);

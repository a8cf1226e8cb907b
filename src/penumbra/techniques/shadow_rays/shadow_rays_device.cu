// CUDA unit (cmake/PenumbraCuda.cmake): shadow-rays' device paths.
#include "penumbra/backends/cuda/launch.cuh"
#include "penumbra/techniques/shadow_rays/shadow_ray_visibility.h"

PENUMBRA_INSTANTIATE_DEVICE(ScatteringLighting<ShadowRayVisibility>);
PENUMBRA_INSTANTIATE_DEVICE(ScatteringLighting<CachedShadowRayVisibility>);

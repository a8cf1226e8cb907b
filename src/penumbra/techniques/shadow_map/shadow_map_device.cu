// CUDA unit (cmake/PenumbraCuda.cmake): shadow-map's device path.
#include "penumbra/backends/cuda/launch.cuh"
#include "penumbra/techniques/shadow_map/shadow_map_kernels.h"

PENUMBRA_INSTANTIATE_DEVICE(ScatteringLighting<ShadowMapVisibility>);

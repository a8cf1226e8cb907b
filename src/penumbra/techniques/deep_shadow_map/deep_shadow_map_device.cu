// CUDA unit (cmake/PenumbraCuda.cmake): deep-shadow-map's device path.
#include "penumbra/backends/cuda/launch.cuh"
#include "penumbra/techniques/deep_shadow_map/deep_shadow_map_kernels.h"

PENUMBRA_INSTANTIATE_DEVICE(ScatteringLighting<DeepShadowVisibility>);

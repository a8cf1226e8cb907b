// CUDA unit (cmake/PenumbraCuda.cmake): cone-shadows's device paths.
#include "penumbra/backends/cuda/launch.cuh"
#include "penumbra/techniques/cone_shadows/cone_march.h"

PENUMBRA_INSTANTIATE_DEVICE(ScatteringLighting<ConeMarch>);
PENUMBRA_INSTANTIATE_DEVICE(ScatteringLighting<CachedConeMarch>);

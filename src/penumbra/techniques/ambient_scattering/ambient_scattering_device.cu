// CUDA unit (cmake/PenumbraCuda.cmake): ambient-scattering's device paths.
#include "penumbra/backends/cuda/launch.cuh"
#include "penumbra/techniques/ambient_scattering/ambient_tube.h"

PENUMBRA_INSTANTIATE_DEVICE(ScatteringLighting<AmbientTube>);
PENUMBRA_INSTANTIATE_DEVICE(ScatteringLighting<CachedAmbientTube>);

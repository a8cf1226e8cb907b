// CUDA unit (cmake/PenumbraCuda.cmake): sat-ao's device paths.
#include "penumbra/backends/cuda/launch.cuh"
#include "penumbra/techniques/sat_ao/ambient_occlusion.h"

PENUMBRA_INSTANTIATE_DEVICE(ScatteringLighting<AmbientOcclusion>);
PENUMBRA_INSTANTIATE_DEVICE(ScatteringLighting<CachedAmbientOcclusion>);

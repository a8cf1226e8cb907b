// CUDA unit (cmake/PenumbraCuda.cmake): cssm's device path.
#include "penumbra/backends/cuda/launch.cuh"
#include "penumbra/techniques/cssm/cssm_kernels.h"

PENUMBRA_INSTANTIATE_DEVICE(ScatteringLighting<CssmVisibility>);

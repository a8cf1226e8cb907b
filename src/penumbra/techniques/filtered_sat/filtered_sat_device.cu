// CUDA unit (cmake/PenumbraCuda.cmake): filtered-sat's device paths.
#include "penumbra/backends/cuda/launch.cuh"
#include "penumbra/techniques/filtered_sat/filtered_visibility.h"

PENUMBRA_INSTANTIATE_DEVICE(ScatteringLighting<FilteredVisibility>);
PENUMBRA_INSTANTIATE_DEVICE(ScatteringLighting<CachedFilteredVisibility>);

// CUDA unit (cmake/PenumbraCuda.cmake): the device paths of the lightings the
// render layer itself declares (lighting.h): emission-absorption and phong.
#include "penumbra/backends/cuda/launch.cuh"
#include "penumbra/render/lighting.h"

PENUMBRA_INSTANTIATE_DEVICE(EmissionLighting);
PENUMBRA_INSTANTIATE_DEVICE(ScatteringLighting<NoShadows>);

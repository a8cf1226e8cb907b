#include "penumbra/techniques/convolution/light_propagation.h"

#include "penumbra/base/parallel.h"

namespace penumbra {

void convolve_slab(const SlabFrame& frame, const SlabKernel& kernel, const float* previous, float* incoming,
                   float depth) {
  const SlabMapping mapping = slab_mapping(frame, depth);
  parallel_for(0, frame.height, [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t y = first; y < last; ++y) {
      for (int x = 0; x < frame.width; ++x) {
        incoming[x + frame.width * int(y)] = convolve_texel_mapped(frame, mapping, kernel, previous, x, int(y));
      }
    }
  });
}

}  // namespace penumbra

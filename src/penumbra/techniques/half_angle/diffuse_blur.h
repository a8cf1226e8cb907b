#pragma once
// half-angle's diffuse blur (Kniss et al. 2003): after each slice the
// forward-scattered light in the light buffer spreads sideways by a Gaussian
// (forward_scattering.h gives the variance per slice). Every texel that has
// been attenuated so far must spread, not only those under the current
// slice: light that has left the slice's footprint keeps diffusing, and may
// reach the footprint of a later slice.
#include "penumbra/base/math.h"

#include <vector>

namespace penumbra {

struct TexelRect {
  int x0, y0, x1, y1;  // [x0, x1) x [y0, y1); empty when x1 <= x0 or y1 <= y0
};

// One slice's blur of the diffuse channels (y, z, w) of the n x n buffer,
// `variance` texels^2 along x and y. `lit` is the rectangle of texels that
// may differ from the unlit constant (what earlier slices attenuated and
// their blur spread); it grows by the slice's own rectangle `slice` and by a
// texel per blur pass, and the blur covers it, which is the same as blurring
// the whole buffer. Passes of the binomial [w, 1 - 2w, w], edges clamped.
// Each pass writes `scratch` inside `lit` and then swaps it with `buffer`
// (no copy back), so `scratch` must equal `buffer` outside `lit` (both the
// unlit constant), and `buffer.data()` changes.
void blur_after_slice(std::vector<vec4>& buffer, std::vector<vec4>& scratch, int n, TexelRect slice, TexelRect& lit,
                      vec2 variance);

}  // namespace penumbra

#include "penumbra/techniques/half_angle/diffuse_blur.h"

#include "penumbra/base/parallel.h"

#include <algorithm>
#include <cmath>

namespace penumbra {
namespace {

bool empty(const TexelRect& r) { return r.x1 <= r.x0 || r.y1 <= r.y0; }

// One texel of a pass: the diffuse channels (1..3) of `c` blurred with its
// neighbours `a` and `b`, the direct one (0) kept.
inline void blur_texel(const float* c, const float* a, const float* b, float keep, float w, float* out) {
  out[0] = c[0];
  for (int k = 1; k < 4; ++k) out[k] = keep * c[k] + w * (a[k] + b[k]);
}

void blur_axis(std::vector<vec4>& buffer, std::vector<vec4>& scratch, int n, TexelRect& r, bool along_x, float v) {
  if (!(v > 1e-4f)) return;
  const int passes = int(std::ceil(v / 0.5f));
  const float w = v / (2.0f * float(passes));
  const float keep = 1.0f - 2.0f * w;
  const std::size_t row_floats = 4 * std::size_t(n);
  for (int pass = 0; pass < passes; ++pass) {
    if (along_x) {
      r.x0 = std::max(r.x0 - 1, 0);
      r.x1 = std::min(r.x1 + 1, n);
    } else {
      r.y0 = std::max(r.y0 - 1, 0);
      r.y1 = std::min(r.y1 + 1, n);
    }
    // The rect's rows as runs of floats, 4 per texel: a texel's neighbours
    // are 4 floats away along x and a row away along y (the buffer's edges
    // clamp: a texel there is its own neighbour). The interior loop has no
    // branch, so the compiler runs it on vectors.
    parallel_for(r.y0, r.y1, [&](std::int64_t first, std::int64_t last) {
      for (std::int64_t y = first; y < last; ++y) {
        const float* row = &buffer[std::size_t(n) * std::size_t(y)].x;
        float* out = &scratch[std::size_t(n) * std::size_t(y)].x;
        int x0 = r.x0, x1 = r.x1;
        std::ptrdiff_t before = -4, after = 4;
        if (along_x) {
          if (x0 == 0) {
            blur_texel(row, row, row + 4, keep, w, out);
            ++x0;
          }
          if (x1 == n && x1 > x0) {
            const std::size_t j = 4 * std::size_t(n - 1);
            blur_texel(row + j, row + j - 4, row + j, keep, w, out + j);
            --x1;
          }
        } else {
          before = y > 0 ? -std::ptrdiff_t(row_floats) : 0;
          after = y + 1 < n ? std::ptrdiff_t(row_floats) : 0;
        }
        for (std::size_t j = 4 * std::size_t(x0); j < 4 * std::size_t(x1); ++j) {
          const float blurred = keep * row[j] + w * (row[std::ptrdiff_t(j) + before] + row[std::ptrdiff_t(j) + after]);
          out[j] = (j & 3) == 0 ? row[j] : blurred;
        }
      }
    });
    // The pass's result becomes the buffer: outside r both hold the unlit
    // constant (blur_after_slice's precondition), inside it scratch is new.
    buffer.swap(scratch);
  }
}

}  // namespace

void blur_after_slice(std::vector<vec4>& buffer, std::vector<vec4>& scratch, int n, TexelRect slice, TexelRect& lit,
                      vec2 variance) {
  if (!empty(slice)) {
    lit = empty(lit) ? slice
                     : TexelRect{std::min(lit.x0, slice.x0), std::min(lit.y0, slice.y0), std::max(lit.x1, slice.x1),
                                 std::max(lit.y1, slice.y1)};
  }
  if (empty(lit)) return;
  blur_axis(buffer, scratch, n, lit, true, variance.x);
  blur_axis(buffer, scratch, n, lit, false, variance.y);
}

}  // namespace penumbra

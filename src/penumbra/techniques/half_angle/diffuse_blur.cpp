#include "penumbra/techniques/half_angle/diffuse_blur.h"

#include "penumbra/base/parallel.h"

#include <algorithm>
#include <cmath>

namespace penumbra {
namespace {

bool empty(const TexelRect& r) { return r.x1 <= r.x0 || r.y1 <= r.y0; }

void blur_axis(std::vector<vec4>& buffer, std::vector<vec4>& scratch, int n, TexelRect& r, bool along_x, float v) {
  if (!(v > 1e-4f)) return;
  const int passes = int(std::ceil(v / 0.5f));
  const float w = v / (2.0f * float(passes));
  for (int pass = 0; pass < passes; ++pass) {
    if (along_x) {
      r.x0 = std::max(r.x0 - 1, 0);
      r.x1 = std::min(r.x1 + 1, n);
    } else {
      r.y0 = std::max(r.y0 - 1, 0);
      r.y1 = std::min(r.y1 + 1, n);
    }
    parallel_for(r.y0, r.y1, [&](std::int64_t first, std::int64_t last) {
      for (std::int64_t y = first; y < last; ++y) {
        for (int x = r.x0; x < r.x1; ++x) {
          const int i = x + n * int(y);
          const int prev = along_x ? (x > 0 ? i - 1 : i) : (y > 0 ? i - n : i);
          const int next = along_x ? (x + 1 < n ? i + 1 : i) : (y + 1 < n ? i + n : i);
          const vec4 c = buffer[std::size_t(i)], a = buffer[std::size_t(prev)], b = buffer[std::size_t(next)];
          const vec3 out = (1.0f - 2.0f * w) * vec3(c.y, c.z, c.w) + w * (vec3(a.y, a.z, a.w) + vec3(b.y, b.z, b.w));
          scratch[std::size_t(i)] = vec4(c.x, out);
        }
      }
    });
    for (int y = r.y0; y < r.y1; ++y) {
      std::copy(scratch.begin() + (r.x0 + n * y), scratch.begin() + (r.x1 + n * y), buffer.begin() + (r.x0 + n * y));
    }
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

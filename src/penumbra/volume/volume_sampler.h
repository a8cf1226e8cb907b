#pragma once
// VolumeSampler<T>: trilinear sampling and central-difference gradients of a
// grid of voxel type T in index space. Hot loops dispatch on the voxel type
// once (with_sampler in volume_view.h) and then sample through this typed
// accessor, so the per-sample code has no type switch and inlines fully.
#include "penumbra/base/math.h"

#include <cstdint>
#include <type_traits>

namespace penumbra {

template <class T> struct VolumeSampler {
  // Samples of integer grids are always finite, so the TF lookup can skip
  // its NaN/inf check.
  static constexpr bool kAlwaysFinite = std::is_integral_v<T>;

  const T* data = nullptr;
  ivec3 dims{0};
  ivec3 max_base{0};  // largest cell origin: dims - 2, at least 0
  vec3 upper{0.0f};   // dims - 1
  std::int64_t stride_x = 0, stride_y = 0, stride_z = 0;  // 0 along axes one voxel thick

  VolumeSampler() = default;
  PENUMBRA_HD VolumeSampler(const void* voxels, ivec3 grid)
      : data(static_cast<const T*>(voxels)),
        dims(grid),
        max_base(glm::max(grid - 2, ivec3(0))),
        upper(vec3(grid - 1)),
        stride_x(grid.x > 1 ? 1 : 0),
        stride_y(grid.y > 1 ? std::int64_t(grid.x) : 0),
        stride_z(grid.z > 1 ? std::int64_t(grid.x) * grid.y : 0) {}

  // Trilinear sample at an index-space position, clamped to the grid.
  PENUMBRA_HD PENUMBRA_FORCE_INLINE float operator()(vec3 p) const {
    p = glm::clamp(p, vec3(0.0f), upper);
    const ivec3 i0 = glm::min(ivec3(p), max_base);
    const vec3 f = glm::min(p - vec3(i0), vec3(1.0f));
    const T* c = data + i0.x + std::int64_t(dims.x) * (i0.y + std::int64_t(dims.y) * i0.z);
    const float c000 = float(c[0]), c100 = float(c[stride_x]);
    const float c010 = float(c[stride_y]), c110 = float(c[stride_x + stride_y]);
    const float c001 = float(c[stride_z]), c101 = float(c[stride_x + stride_z]);
    const float c011 = float(c[stride_y + stride_z]), c111 = float(c[stride_x + stride_y + stride_z]);
    const float x00 = c000 + f.x * (c100 - c000);
    const float x10 = c010 + f.x * (c110 - c010);
    const float x01 = c001 + f.x * (c101 - c001);
    const float x11 = c011 + f.x * (c111 - c011);
    const float y0 = x00 + f.y * (x10 - x00);
    const float y1 = x01 + f.y * (x11 - x01);
    return y0 + f.z * (y1 - y0);
  }

  // Central differences of the trilinear field with a one-voxel step,
  // one-sided at the grid border so linear fields are reproduced exactly.
  // Value units per index unit.
  PENUMBRA_HD vec3 gradient(vec3 p) const {
    vec3 g(0.0f);
    p = glm::clamp(p, vec3(0.0f), upper);
    for (int axis = 0; axis < 3; ++axis) {
      vec3 lo = p;
      vec3 hi = p;
      lo[axis] = glm::max(p[axis] - 1.0f, 0.0f);
      hi[axis] = glm::min(p[axis] + 1.0f, upper[axis]);
      const float h = hi[axis] - lo[axis];
      if (h > 0.0f) g[axis] = ((*this)(hi) - (*this)(lo)) / h;
    }
    return g;
  }
};

}  // namespace penumbra

#pragma once
// Trilinear sampling and central-difference gradients of a voxel grid in
// index space, written once over a lane type (base/lanes.h): one position,
// or a packet of positions gathered at once.
//
// VolumeSampler<T> is the typed accessor hot scalar loops use after
// dispatching on the voxel type once (with_sampler in volume_view.h), so the
// per-sample code has no type switch and inlines fully. AnyVoxelSampler
// switches on the type per call instead: packets use it, where one
// predictable branch per 8 or 16 samples costs less than compiling every
// kernel once per voxel type.
#include "penumbra/base/lanes.h"
#include "penumbra/base/math.h"
#include "penumbra/volume/voxel_type.h"

#include <cstdint>
#include <type_traits>

namespace penumbra {

// The grid geometry every sampler shares.
struct VoxelGrid {
  ivec3 dims{0};
  ivec3 max_base{0};  // largest cell origin: dims - 2, at least 0
  vec3 upper{0.0f};   // dims - 1
  std::int64_t stride_x = 0, stride_y = 0, stride_z = 0;  // 0 along axes one voxel thick
  std::int64_t count = 0;                                 // voxels

  VoxelGrid() = default;
  PENUMBRA_HD explicit VoxelGrid(ivec3 grid)
      : dims(grid),
        max_base(glm::max(grid - 2, ivec3(0))),
        upper(vec3(grid - 1)),
        stride_x(grid.x > 1 ? 1 : 0),
        stride_y(grid.y > 1 ? std::int64_t(grid.x) : 0),
        stride_z(grid.z > 1 ? std::int64_t(grid.x) * grid.y : 0),
        count(std::int64_t(grid.x) * grid.y * grid.z) {}
};

// The grid cell of index-space positions, clamped to the grid: the offset of
// its first voxel and the fractions inside it, for trilinear interpolation of
// voxels or of NormalVolume's texels.
template <class L> struct GridCell {
  typename L::Index base;
  typename L::Float fx, fy, fz;

  PENUMBRA_HD PENUMBRA_FORCE_INLINE GridCell(const VoxelGrid& g, const typename L::Vec3& p) {
    using F = typename L::Float;
    using I = typename L::Int;
    using X = typename L::Index;
    const F px = clamp(p.x, F(0.0f), F(g.upper.x));
    const F py = clamp(p.y, F(0.0f), F(g.upper.y));
    const F pz = clamp(p.z, F(0.0f), F(g.upper.z));
    const I ix = min(to_int_nonnegative(px), I(g.max_base.x));
    const I iy = min(to_int_nonnegative(py), I(g.max_base.y));
    const I iz = min(to_int_nonnegative(pz), I(g.max_base.z));
    // In [0, 1] without a clamp: p <= upper = max_base + 1 where an axis has
    // two voxels or more, and p = ix = 0 where it has one.
    fx = px - to_float(ix);
    fy = py - to_float(iy);
    fz = pz - to_float(iz);
    base = X(ix) + X(g.dims.x) * (X(iy) + X(g.dims.y) * X(iz));
  }
};

// Trilinear sample in a grid cell (GridCell of the same grid).
template <class L, class T>
PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Float trilinear_at(const VoxelGrid& g, const T* data,
                                                                 const GridCell<L>& cell) {
  using F = typename L::Float;
  using X = typename L::Index;
  const X& base = cell.base;
  const F &fx = cell.fx, &fy = cell.fy, &fz = cell.fz;
  F c000, c100, c010, c110, c001, c101, c011, c111;
  load_voxel_pair(data, base, g.stride_x, g.count, c000, c100);
  load_voxel_pair(data, base + X(g.stride_y), g.stride_x, g.count, c010, c110);
  load_voxel_pair(data, base + X(g.stride_z), g.stride_x, g.count, c001, c101);
  load_voxel_pair(data, base + X(g.stride_y + g.stride_z), g.stride_x, g.count, c011, c111);
  const F x00 = c000 + fx * (c100 - c000);
  const F x10 = c010 + fx * (c110 - c010);
  const F x01 = c001 + fx * (c101 - c001);
  const F x11 = c011 + fx * (c111 - c011);
  const F y0 = x00 + fy * (x10 - x00);
  const F y1 = x01 + fy * (x11 - x01);
  return y0 + fz * (y1 - y0);
}

// Trilinear sample at index-space positions, clamped to the grid.
template <class L, class T>
PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Float trilinear(const VoxelGrid& g, const T* data,
                                                              const typename L::Vec3& p) {
  return trilinear_at<L>(g, data, GridCell<L>(g, p));
}

// Central differences of the trilinear field with a one-voxel step,
// one-sided at the grid border so linear fields are reproduced exactly.
// Value units per index unit. `sample` is the sampler's trilinear lookup.
template <class L, class Sample>
PENUMBRA_HD typename L::Vec3 central_gradient(const VoxelGrid& g, typename L::Vec3 p, const Sample& sample) {
  using F = typename L::Float;
  using V = typename L::Vec3;
  p = V(clamp(p.x, F(0.0f), F(g.upper.x)), clamp(p.y, F(0.0f), F(g.upper.y)), clamp(p.z, F(0.0f), F(g.upper.z)));
  V gradient(0.0f);
  for (int axis = 0; axis < 3; ++axis) {
    V lo = p;
    V hi = p;
    lo[axis] = max(p[axis] - 1.0f, F(0.0f));
    hi[axis] = min(p[axis] + 1.0f, F(g.upper[axis]));
    const F h = hi[axis] - lo[axis];
    const auto has_width = h > 0.0f;
    if (none(has_width)) continue;
    gradient[axis] = select(has_width, (sample(hi) - sample(lo)) / h, F(0.0f));
  }
  return gradient;
}

template <class T> struct VolumeSampler {
  // Samples of integer grids are always finite, so the TF lookup can skip
  // its NaN/inf check.
  static constexpr bool kAlwaysFinite = std::is_integral_v<T>;

  VoxelGrid grid;
  const T* data = nullptr;

  VolumeSampler() = default;
  PENUMBRA_HD VolumeSampler(const void* voxels, ivec3 dims) : grid(dims), data(static_cast<const T*>(voxels)) {}

  PENUMBRA_HD static constexpr bool all_finite() { return kAlwaysFinite; }

  template <class L> PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Float sample(const typename L::Vec3& p) const {
    return trilinear<L>(grid, data, p);
  }
  // The sample in a cell of `grid` (the marching loop keeps the cell for the normals).
  template <class L> PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Float sample_at(const GridCell<L>& cell) const {
    return trilinear_at<L>(grid, data, cell);
  }
  PENUMBRA_HD PENUMBRA_FORCE_INLINE float operator()(vec3 p) const { return sample<ScalarLanes>(p); }

  template <class L> PENUMBRA_HD typename L::Vec3 gradient(const typename L::Vec3& p) const {
    return central_gradient<L>(grid, p, [&](const typename L::Vec3& q) { return sample<L>(q); });
  }
  PENUMBRA_HD vec3 gradient(vec3 p) const { return gradient<ScalarLanes>(p); }
};

// The voxel types packets sample (a 32-bit gather per lane reaches them);
// uint32 and float64 volumes render on the scalar path.
PENUMBRA_HD constexpr bool packet_voxel_type(VoxelType type) {
  return type != VoxelType::UInt32 && type != VoxelType::Float64;
}

// A sampler that switches on the voxel type per call (packets; see above).
struct AnyVoxelSampler {
  VoxelGrid grid;
  const void* data = nullptr;
  VoxelType type = VoxelType::UInt8;

  AnyVoxelSampler() = default;
  PENUMBRA_HD AnyVoxelSampler(const void* voxels, ivec3 dims, VoxelType voxel_type)
      : grid(dims), data(voxels), type(voxel_type) {}

  // Not known at compile time: kernels take the TF lookup that checks for
  // NaN (the float types may hold it).
  static constexpr bool kAlwaysFinite = false;
  PENUMBRA_HD bool all_finite() const { return type != VoxelType::Float32 && type != VoxelType::Float64; }

  template <class L> PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Float sample(const typename L::Vec3& p) const {
    return sample_at<L>(GridCell<L>(grid, p));
  }
  // The sample in a cell of `grid` (the marching loop keeps the cell for the normals).
  template <class L> PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Float sample_at(const GridCell<L>& c) const {
    switch (type) {
      case VoxelType::UInt8: return trilinear_at<L>(grid, static_cast<const std::uint8_t*>(data), c);
      case VoxelType::Int8: return trilinear_at<L>(grid, static_cast<const std::int8_t*>(data), c);
      case VoxelType::UInt16: return trilinear_at<L>(grid, static_cast<const std::uint16_t*>(data), c);
      case VoxelType::Int16: return trilinear_at<L>(grid, static_cast<const std::int16_t*>(data), c);
      case VoxelType::Int32: return trilinear_at<L>(grid, static_cast<const std::int32_t*>(data), c);
      case VoxelType::Float32: return trilinear_at<L>(grid, static_cast<const float*>(data), c);
      case VoxelType::UInt32:
      case VoxelType::Float64: break;  // not packet types (packet_voxel_type)
    }
    if constexpr (L::kWidth == 1) {
      if (type == VoxelType::UInt32) return trilinear_at<L>(grid, static_cast<const std::uint32_t*>(data), c);
      return trilinear_at<L>(grid, static_cast<const double*>(data), c);
    } else {
      return typename L::Float(0.0f);
    }
  }

  template <class L> PENUMBRA_HD typename L::Vec3 gradient(const typename L::Vec3& p) const {
    return central_gradient<L>(grid, p, [&](const typename L::Vec3& q) { return sample<L>(q); });
  }

  // The scalar interface of VolumeSampler (the device's kernels).
  PENUMBRA_HD float operator()(vec3 p) const { return sample<ScalarLanes>(p); }
  PENUMBRA_HD vec3 gradient(vec3 p) const { return gradient<ScalarLanes>(p); }
};

}  // namespace penumbra

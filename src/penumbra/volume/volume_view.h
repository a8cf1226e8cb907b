#pragma once
// VolumeView: the plain struct that kernels read one frame of a volume through.
// Index space has voxel centres at integer coordinates 0..dims-1;
// world = origin + index * spacing (world_from_index = translate(origin) *
// scale(spacing)). Sampling is trilinear and clamps to the grid.
#include "penumbra/base/math.h"
#include "penumbra/base/ray.h"
#include "penumbra/volume/voxel_type.h"

#include <cstdint>

namespace penumbra {

namespace detail {

template <class T>
PENUMBRA_HD inline float trilinear(const T* data, ivec3 dims, vec3 p) {
  const vec3 upper = vec3(dims - 1);
  p = glm::clamp(p, vec3(0.0f), upper);
  const ivec3 i0 = glm::max(glm::min(ivec3(p), dims - 2), ivec3(0));
  const vec3 f = glm::min(p - vec3(i0), vec3(1.0f));
  const std::int64_t sx = dims.x > 1 ? 1 : 0;
  const std::int64_t sy = dims.y > 1 ? std::int64_t(dims.x) : 0;
  const std::int64_t sz = dims.z > 1 ? std::int64_t(dims.x) * dims.y : 0;
  const T* c = data + i0.x + std::int64_t(dims.x) * (i0.y + std::int64_t(dims.y) * i0.z);
  const float c000 = float(c[0]), c100 = float(c[sx]);
  const float c010 = float(c[sy]), c110 = float(c[sx + sy]);
  const float c001 = float(c[sz]), c101 = float(c[sx + sz]);
  const float c011 = float(c[sy + sz]), c111 = float(c[sx + sy + sz]);
  const float x00 = c000 + f.x * (c100 - c000);
  const float x10 = c010 + f.x * (c110 - c010);
  const float x01 = c001 + f.x * (c101 - c001);
  const float x11 = c011 + f.x * (c111 - c011);
  const float y0 = x00 + f.y * (x10 - x00);
  const float y1 = x01 + f.y * (x11 - x01);
  return y0 + f.z * (y1 - y0);
}

// Central differences of the trilinear field with a one-voxel step, one-sided
// at the grid border so that linear fields are reproduced exactly everywhere.
// Result in value units per index unit.
template <class T>
PENUMBRA_HD inline vec3 gradient_index_space(const T* data, ivec3 dims, vec3 p) {
  vec3 g(0.0f);
  const vec3 upper = vec3(dims - 1);
  p = glm::clamp(p, vec3(0.0f), upper);
  for (int axis = 0; axis < 3; ++axis) {
    vec3 lo = p;
    vec3 hi = p;
    lo[axis] = glm::max(p[axis] - 1.0f, 0.0f);
    hi[axis] = glm::min(p[axis] + 1.0f, upper[axis]);
    const float h = hi[axis] - lo[axis];
    if (h > 0.0f) g[axis] = (trilinear(data, dims, hi) - trilinear(data, dims, lo)) / h;
  }
  return g;
}

}  // namespace detail

struct VolumeView {
  const void* data = nullptr;
  VoxelType type = VoxelType::UInt8;
  ivec3 dims{0};
  vec3 spacing{1.0f};
  vec3 origin{0.0f};

  PENUMBRA_HD vec3 index_from_world(vec3 p) const { return (p - origin) / spacing; }
  PENUMBRA_HD vec3 world_from_index(vec3 i) const { return origin + i * spacing; }
  PENUMBRA_HD Box3 world_box() const { return Box3{origin, origin + vec3(dims - 1) * spacing}; }
  PENUMBRA_HD float min_spacing() const { return min_component(spacing); }

  PENUMBRA_HD float voxel(ivec3 i) const {
    const std::int64_t offset = i.x + std::int64_t(dims.x) * (i.y + std::int64_t(dims.y) * i.z);
    return visit_voxel_type(type, [&](auto tag) {
      using T = decltype(tag);
      return float(static_cast<const T*>(data)[offset]);
    });
  }

  // Trilinear sample at an index-space position.
  PENUMBRA_HD float sample_index(vec3 p) const {
    return visit_voxel_type(type, [&](auto tag) {
      using T = decltype(tag);
      return detail::trilinear(static_cast<const T*>(data), dims, p);
    });
  }

  PENUMBRA_HD float sample(vec3 world) const { return sample_index(index_from_world(world)); }

  // Gradient of the scalar field in value units per world unit.
  PENUMBRA_HD vec3 gradient_index(vec3 p) const {
    const vec3 g = visit_voxel_type(type, [&](auto tag) {
      using T = decltype(tag);
      return detail::gradient_index_space(static_cast<const T*>(data), dims, p);
    });
    return g / spacing;
  }

  PENUMBRA_HD vec3 gradient(vec3 world) const { return gradient_index(index_from_world(world)); }
};

}  // namespace penumbra

#pragma once
// VolumeView: the plain struct that kernels read one frame of a volume through.
// Index space has voxel centres at integer coordinates 0..dims-1;
// world = origin + index * spacing (world_from_index = translate(origin) *
// scale(spacing)). Sampling is trilinear and clamps to the grid.
#include "penumbra/base/math.h"
#include "penumbra/base/ray.h"
#include "penumbra/volume/volume_sampler.h"
#include "penumbra/volume/voxel_type.h"

#include <cstdint>

namespace penumbra {


struct VolumeView {
  const void* data = nullptr;
  VoxelType type = VoxelType::UInt8;
  ivec3 dims{0};
  vec3 spacing{1.0f};
  vec3 origin{0.0f};

  // Written over a lane type (base/lanes.h); the vec3 form is its one-lane
  // instance.
  template <class L>
  PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Vec3 index_from_world(const typename L::Vec3& p) const {
    using V = typename L::Vec3;
    return (p - V(origin)) / V(spacing);
  }
  PENUMBRA_HD vec3 index_from_world(vec3 p) const { return index_from_world<ScalarLanes>(p); }
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

  // Trilinear sample at an index-space position (see VolumeSampler for the
  // typed version that hot loops use).
  PENUMBRA_HD float sample_index(vec3 p) const;

  PENUMBRA_HD float sample(vec3 world) const { return sample_index(index_from_world(world)); }

  // Gradient of the scalar field in value units per world unit.
  PENUMBRA_HD vec3 gradient_index(vec3 p) const;

  PENUMBRA_HD vec3 gradient(vec3 world) const { return gradient_index(index_from_world(world)); }
};

// Calls f(VolumeSampler<T>) with T the view's voxel type.
template <class F> PENUMBRA_HD decltype(auto) with_sampler(const VolumeView& view, F&& f) {
  return visit_voxel_type(view.type, [&](auto tag) { return f(VolumeSampler<decltype(tag)>(view.data, view.dims)); });
}

PENUMBRA_HD inline float VolumeView::sample_index(vec3 p) const {
  return with_sampler(*this, [&](const auto& sampler) { return sampler(p); });
}

PENUMBRA_HD inline vec3 VolumeView::gradient_index(vec3 p) const {
  return with_sampler(*this, [&](const auto& sampler) { return sampler.gradient(p); }) / spacing;
}

}  // namespace penumbra

#pragma once
// Precomputed shading normals: per voxel, the central-difference gradient in
// world units, normalised and quantised to int8 (x, y, z, unused), so Phong
// shading interpolates one 4-byte texel trilinearly instead of taking six
// trilinear samples per lit sample (the same trade VTK's CPU mappers make).
// Quantisation costs < 0.5 degree of normal direction; VolumeSampler::gradient
// stays the exact reference. Zero gradients are stored as (0, 0, 0).
#include "penumbra/base/math.h"
#include "penumbra/volume/volume_sampler.h"
#include "penumbra/volume/volume_view.h"

#include <cstdint>
#include <vector>

namespace penumbra {

struct NormalView {
  const std::int8_t* texels = nullptr;  // 4 per voxel: x, y, z, 0
  VoxelGrid grid;

  // Interpolated gradient direction (not unit length: shorter where the
  // neighbouring directions disagree, zero in homogeneous regions), at
  // index-space positions: the trilinear interpolation of trilinear() on
  // 4-byte texels.
  template <class L> PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Vec3 sample(const typename L::Vec3& p) const {
    return sample_at<L>(GridCell<L>(grid, p));
  }
  // The same in a cell of the volume's grid (the normals have the volume's dims).
  template <class L> PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Vec3 sample_at(const GridCell<L>& cell) const {
    using F = typename L::Float;
    using X = typename L::Index;
    using V = typename L::Vec3;
    const X& base = cell.base;
    const F &fx = cell.fx, &fy = cell.fy, &fz = cell.fz;
    const X sy(grid.stride_y), sz(grid.stride_z);
    V c000, c100, c010, c110, c001, c101, c011, c111;
    load_texel_pair_xyz(texels, base, grid.stride_x, c000, c100);
    load_texel_pair_xyz(texels, base + sy, grid.stride_x, c010, c110);
    load_texel_pair_xyz(texels, base + sz, grid.stride_x, c001, c101);
    load_texel_pair_xyz(texels, base + sy + sz, grid.stride_x, c011, c111);
    const V x00 = c000 + fx * (c100 - c000);
    const V x10 = c010 + fx * (c110 - c010);
    const V x01 = c001 + fx * (c101 - c001);
    const V x11 = c011 + fx * (c111 - c011);
    const V y0 = x00 + fy * (x10 - x00);
    const V y1 = x01 + fy * (x11 - x01);
    return (y0 + fz * (y1 - y0)) * (1.0f / 127.0f);
  }
  PENUMBRA_HD PENUMBRA_FORCE_INLINE vec3 sample(vec3 p) const { return sample<ScalarLanes>(p); }
};

class NormalVolume {
 public:
  NormalVolume() = default;
  // Checks the memory budget first (4 bytes per voxel).
  explicit NormalVolume(const VolumeView& volume);

  NormalView view() const { return NormalView{texels_.data(), VoxelGrid(dims_)}; }
  std::uint64_t bytes() const { return texels_.size(); }
  bool empty() const { return texels_.empty(); }

 private:
  std::vector<std::int8_t> texels_;
  ivec3 dims_{0};
};

}  // namespace penumbra

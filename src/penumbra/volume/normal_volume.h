#pragma once
// Precomputed shading normals: per voxel, the central-difference gradient in
// world units, normalised and quantised to int8 (x, y, z, unused), so Phong
// shading interpolates one 4-byte texel trilinearly instead of taking six
// trilinear samples per lit sample (the same trade VTK's CPU mappers make).
// Quantisation costs < 0.5 degree of normal direction; VolumeSampler::gradient
// stays the exact reference. Zero gradients are stored as (0, 0, 0).
#include "penumbra/base/math.h"
#include "penumbra/volume/volume_view.h"

#include <cstdint>
#include <vector>

namespace penumbra {

struct NormalView {
  const std::int8_t* texels = nullptr;  // 4 per voxel: x, y, z, 0
  ivec3 dims{0};

  // Interpolated gradient direction (not unit length: shorter where the
  // neighbouring directions disagree, zero in homogeneous regions), at an
  // index-space position.
  PENUMBRA_HD PENUMBRA_FORCE_INLINE vec3 sample(vec3 p) const {
    const vec3 upper = vec3(dims - 1);
    p = glm::clamp(p, vec3(0.0f), upper);
    const ivec3 i0 = glm::min(ivec3(p), glm::max(dims - 2, ivec3(0)));
    const vec3 f = glm::min(p - vec3(i0), vec3(1.0f));
    const std::int64_t sx = dims.x > 1 ? 4 : 0;
    const std::int64_t sy = dims.y > 1 ? 4 * std::int64_t(dims.x) : 0;
    const std::int64_t sz = dims.z > 1 ? 4 * std::int64_t(dims.x) * dims.y : 0;
    const std::int8_t* c = texels + 4 * (i0.x + std::int64_t(dims.x) * (i0.y + std::int64_t(dims.y) * i0.z));
    // Lane by lane over the four bytes of a texel, so the compiler can keep
    // the whole interpolation in one vector register.
    float r[4];
    for (int k = 0; k < 4; ++k) {
      const float x00 = float(c[k]) + f.x * (float(c[sx + k]) - float(c[k]));
      const float x10 = float(c[sy + k]) + f.x * (float(c[sx + sy + k]) - float(c[sy + k]));
      const float x01 = float(c[sz + k]) + f.x * (float(c[sx + sz + k]) - float(c[sz + k]));
      const float x11 = float(c[sy + sz + k]) + f.x * (float(c[sx + sy + sz + k]) - float(c[sy + sz + k]));
      const float y0 = x00 + f.y * (x10 - x00);
      const float y1 = x01 + f.y * (x11 - x01);
      r[k] = y0 + f.z * (y1 - y0);
    }
    return vec3(r[0], r[1], r[2]) * (1.0f / 127.0f);
  }
};

class NormalVolume {
 public:
  NormalVolume() = default;
  // Checks the memory budget first (4 bytes per voxel).
  explicit NormalVolume(const VolumeView& volume);

  NormalView view() const { return NormalView{texels_.data(), dims_}; }
  std::uint64_t bytes() const { return texels_.size(); }
  bool empty() const { return texels_.empty(); }

 private:
  std::vector<std::int8_t> texels_;
  ivec3 dims_{0};
};

}  // namespace penumbra

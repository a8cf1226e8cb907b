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
  PENUMBRA_HD vec3 sample(vec3 p) const {
    const vec3 upper = vec3(dims - 1);
    p = glm::clamp(p, vec3(0.0f), upper);
    const ivec3 i0 = glm::min(ivec3(p), glm::max(dims - 2, ivec3(0)));
    const vec3 f = glm::min(p - vec3(i0), vec3(1.0f));
    const std::int64_t sx = dims.x > 1 ? 4 : 0;
    const std::int64_t sy = dims.y > 1 ? 4 * std::int64_t(dims.x) : 0;
    const std::int64_t sz = dims.z > 1 ? 4 * std::int64_t(dims.x) * dims.y : 0;
    const std::int8_t* c = texels + 4 * (i0.x + std::int64_t(dims.x) * (i0.y + std::int64_t(dims.y) * i0.z));
    auto load = [](const std::int8_t* t) { return vec3(float(t[0]), float(t[1]), float(t[2])); };
    const vec3 x00 = glm::mix(load(c), load(c + sx), f.x);
    const vec3 x10 = glm::mix(load(c + sy), load(c + sx + sy), f.x);
    const vec3 x01 = glm::mix(load(c + sz), load(c + sx + sz), f.x);
    const vec3 x11 = glm::mix(load(c + sy + sz), load(c + sx + sy + sz), f.x);
    return glm::mix(glm::mix(x00, x10, f.y), glm::mix(x01, x11, f.y), f.z) * (1.0f / 127.0f);
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

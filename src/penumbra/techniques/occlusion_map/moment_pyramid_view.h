#pragma once
// What kernels read of the occlusion map: per level a grid of K moments of
// the normalised data value u in [0, 1] (u, u^2 for the paper's variance
// occlusion map; u .. u^4 with four moments), sampled trilinearly (a weighted
// mean of moments is the moments of the weighted mixture, which is what makes
// the map filterable), and between levels linearly (a fractional mip level).
#include "penumbra/base/math.h"

#include <cstddef>
#include <cstdint>

namespace penumbra {

inline constexpr int kMaxMomentLevels = 8;
// Half-width, in the level's sigmas, of the box whose largest value a
// maximum node holds (the Gaussian kernels' truncation radius).
inline constexpr float kMaximumRadiusSigmas = 2.0f;
// The maxima are stored in 1 / kMaximumSteps of the value range, rounded up
// (one byte a node: an eighth of a two-moment level's floats), so a read is
// never below the true maximum and at most 0.004 above it.
inline constexpr int kMaximumSteps = 255;

struct MomentLevelView {
  const float* texels = nullptr;  // K floats per node, x fastest
  const std::uint8_t* maxima = nullptr;  // one byte per node: the largest u around it, in 255ths rounded up
  ivec3 dims{0};
  vec3 scale{0.0f};  // level nodes per world unit, per axis
};

template <int K> struct MomentPyramidView {
  static_assert(K == 2 || K == 4, "two or four moments");
  using Moments = glm::vec<K, float, glm::defaultp>;

  MomentLevelView levels[kMaxMomentLevels];
  int level_count = 0;
  vec3 origin{0.0f};    // world position of node 0 of every level (the volume's origin)
  float sigma0 = 1.0f;  // world-space standard deviation of level 0's Gaussian region

  // The device copy (backends/device.h): every level's moments mirrored.
  template <class Mirror> MomentPyramidView on_device(Mirror& m) const {
    MomentPyramidView d = *this;
    for (int i = 0; i < level_count; ++i) {
      const MomentLevelView& l = levels[i];
      d.levels[i].texels = m.structure(l.texels, std::size_t(l.dims.x) * l.dims.y * l.dims.z * K, "the moment pyramid");
      d.levels[i].maxima = m.structure(l.maxima, std::size_t(l.dims.x) * l.dims.y * l.dims.z, "the moment pyramid's maxima");
    }
    return d;
  }

  // Level k's region is a Gaussian of standard deviation sigma0 * 2^k.
  PENUMBRA_HD float sigma(float level) const { return sigma0 * glm::exp2(level); }
  // The same at a whole level, without exp2 (exact: 2^level is a power of two).
  PENUMBRA_HD float sigma_at(int level) const { return sigma0 * float(1 << level); }

  PENUMBRA_HD Moments sample(int level, vec3 world) const {
    const MomentLevelView& l = levels[level < 0 ? 0 : (level >= level_count ? level_count - 1 : level)];
    const vec3 p = glm::clamp((world - origin) * l.scale, vec3(0.0f), vec3(l.dims - 1));
    const ivec3 i0 = glm::min(ivec3(p), glm::max(l.dims - 2, ivec3(0)));
    const vec3 f = glm::min(p - vec3(i0), vec3(1.0f));
    const long sx = l.dims.x > 1 ? K : 0;
    const long sy = l.dims.y > 1 ? long(l.dims.x) * K : 0;
    const long sz = l.dims.z > 1 ? long(l.dims.x) * l.dims.y * K : 0;
    const float* c = l.texels + (i0.x + long(l.dims.x) * (i0.y + long(l.dims.y) * i0.z)) * K;
    const Moments x00 = glm::mix(load(c), load(c + sx), f.x);
    const Moments x10 = glm::mix(load(c + sy), load(c + sx + sy), f.x);
    const Moments x01 = glm::mix(load(c + sz), load(c + sx + sz), f.x);
    const Moments x11 = glm::mix(load(c + sy + sz), load(c + sx + sy + sz), f.x);
    return glm::mix(glm::mix(x00, x10, f.y), glm::mix(x01, x11, f.y), f.z);
  }

  // The largest u anywhere in the box of half-width kMaximumRadiusSigmas
  // sigma around `world` (or a larger box): the nearest node's maximum. A
  // fractional level reads the coarser of its two levels.
  PENUMBRA_HD float maximum(float level, vec3 world) const {
    const float top = float(level_count - 1);
    level = level < 0.0f ? 0.0f : (level > top ? top : level);
    const MomentLevelView& l = levels[int(glm::ceil(level))];
    // Rounded to the nearest node, halves up (the coordinates are clamped
    // to >= 0 first, where that is roundf's rounding, without its call).
    const vec3 p = glm::clamp((world - origin) * l.scale, vec3(0.0f), vec3(l.dims - 1));
    ivec3 i(p);
    i += ivec3(glm::greaterThanEqual(p - vec3(i), vec3(0.5f)));
    i = glm::min(i, l.dims - 1);
    return float(l.maxima[i.x + long(l.dims.x) * (i.y + long(l.dims.y) * i.z)]) * (1.0f / float(kMaximumSteps));
  }

  // A fractional level: the moments of the two nearest levels, mixed.
  PENUMBRA_HD Moments sample(float level, vec3 world) const {
    const float top = float(level_count - 1);
    level = level < 0.0f ? 0.0f : (level > top ? top : level);
    const int lo = int(level);
    const float f = level - float(lo);
    if (f <= 0.0f) return sample(lo, world);
    return glm::mix(sample(lo, world), sample(lo + 1, world), f);
  }

 private:
  PENUMBRA_HD static Moments load(const float* p) {
    Moments m;
    for (int i = 0; i < K; ++i) m[i] = p[i];
    return m;
  }
};

}  // namespace penumbra

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

// Calls fn(k, lanes) once for each level k that some lane of `mask` holds in
// `level`, with the mask of those lanes (a packet's lanes may march at
// different levels; a scalar lane makes one call).
template <class L, class Fn>
PENUMBRA_HD PENUMBRA_FORCE_INLINE void for_each_level(typename L::Int level, typename L::Mask mask, Fn&& fn) {
  if constexpr (L::kWidth == 1) {
    if (mask) fn(int(level), mask);
  } else {
    for (int k = 0; k < kMaxMomentLevels && any(mask); ++k) {
      const typename L::Mask at = mask & (level == typename L::Int(k));
      if (none(at)) continue;
      fn(k, at);
      mask = mask & !at;
    }
  }
}

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

  // Level `level`'s trilinear moments at `world`, on any lane type (the
  // level is the same for every lane; positions outside the grid clamp to
  // its edge, so every lane reads inside it).
  template <class L>
  PENUMBRA_HD PENUMBRA_FORCE_INLINE void sample_at(int level, const typename L::Vec3& world,
                                                   typename L::Float (&out)[K]) const {
    using F = typename L::Float;
    using I = typename L::Index;
    const MomentLevelView& l = levels[level < 0 ? 0 : (level >= level_count ? level_count - 1 : level)];
    I node(0);
    I stride[3];
    F frac[3];
    long axis_stride = K;
    for (int a = 0; a < 3; ++a) {
      const F p = clamp((world[a] - origin[a]) * l.scale[a], F(0.0f), F(float(l.dims[a] - 1)));
      const auto i0 = min(to_int_nonnegative(p), typename L::Int(l.dims[a] > 1 ? l.dims[a] - 2 : 0));
      frac[a] = min(p - to_float(i0), F(1.0f));
      node = node + I(i0) * I(axis_stride);
      stride[a] = I(l.dims[a] > 1 ? axis_stride : 0);
      axis_stride *= l.dims[a];
    }
    for (int k = 0; k < K; ++k) {
      const I c = node + I(k);
      const F x00 = lerp<F>(gather(l.texels, c), gather(l.texels, c + stride[0]), frac[0]);
      const F x10 = lerp<F>(gather(l.texels, c + stride[1]), gather(l.texels, c + stride[0] + stride[1]), frac[0]);
      const F x01 = lerp<F>(gather(l.texels, c + stride[2]), gather(l.texels, c + stride[0] + stride[2]), frac[0]);
      const F x11 = lerp<F>(gather(l.texels, c + stride[1] + stride[2]),
                            gather(l.texels, c + stride[0] + stride[1] + stride[2]), frac[0]);
      out[k] = lerp<F>(lerp<F>(x00, x10, frac[1]), lerp<F>(x01, x11, frac[1]), frac[2]);
    }
  }

  PENUMBRA_HD Moments sample(int level, vec3 world) const {
    float m[K];
    sample_at<ScalarLanes>(level, world, m);
    Moments r;
    for (int i = 0; i < K; ++i) r[i] = m[i];
    return r;
  }

  // The nearest node's maximum at a whole level, on any lane type.
  template <class L>
  PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Float maximum_at(int level, const typename L::Vec3& world) const {
    using F = typename L::Float;
    using I = typename L::Index;
    const MomentLevelView& l = levels[level < 0 ? 0 : (level >= level_count ? level_count - 1 : level)];
    I node(0);
    long axis_stride = 1;
    for (int a = 0; a < 3; ++a) {
      // Rounded to the nearest node, halves up (the coordinates are clamped
      // to >= 0 first, where that is roundf's rounding, without its call).
      const F p = clamp((world[a] - origin[a]) * l.scale[a], F(0.0f), F(float(l.dims[a] - 1)));
      auto i = to_int_nonnegative(p);
      i = select(p - to_float(i) >= 0.5f, i + 1, i);
      i = min(i, typename L::Int(l.dims[a] - 1));
      node = node + I(i) * I(axis_stride);
      axis_stride *= l.dims[a];
    }
    return load_voxel(l.maxima, node, std::int64_t(axis_stride)) * (1.0f / float(kMaximumSteps));
  }

  // The largest u anywhere in the box of half-width kMaximumRadiusSigmas
  // sigma around `world` (or a larger box): the nearest node's maximum. A
  // fractional level reads the coarser of its two levels. Each lane at its
  // own level (clamped to the pyramid); lanes off in `lanes` read 0.
  template <class L>
  PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Float maximum_lanes(typename L::Float level,
                                                                   const typename L::Vec3& world,
                                                                   typename L::Mask lanes) const {
    using F = typename L::Float;
    level = clamp(level, F(0.0f), F(float(level_count - 1)));
    const auto whole = to_int_nonnegative(level);
    const auto coarser = select(level > to_float(whole), whole + 1, whole);
    F top(0.0f);
    for_each_level<L>(coarser, lanes,
                      [&](int k, typename L::Mask at) { top = select(at, maximum_at<L>(k, world), top); });
    return top;
  }
  PENUMBRA_HD float maximum(float level, vec3 world) const { return maximum_lanes<ScalarLanes>(level, world, true); }

  // A fractional level: the moments of the two nearest levels, mixed. Each
  // lane at its own level; lanes off in `lanes` read 0.
  template <class L>
  PENUMBRA_HD PENUMBRA_FORCE_INLINE void sample_lanes(typename L::Float level, const typename L::Vec3& world,
                                                      typename L::Mask lanes, typename L::Float (&out)[K]) const {
    using F = typename L::Float;
    using M = typename L::Mask;
    level = clamp(level, F(0.0f), F(float(level_count - 1)));
    const auto whole = to_int_nonnegative(level);
    const F f = level - to_float(whole);
    for (int i = 0; i < K; ++i) out[i] = F(0.0f);
    for_each_level<L>(whole, lanes, [&](int k, M at) {
      F lo[K];
      sample_at<L>(k, world, lo);
      const M mix = at & (f > 0.0f);
      if (any(mix)) {
        F hi[K];
        sample_at<L>(k + 1, world, hi);
        for (int i = 0; i < K; ++i) lo[i] = select(mix, lerp<F>(lo[i], hi[i], f), lo[i]);
      }
      for (int i = 0; i < K; ++i) out[i] = select(at, lo[i], out[i]);
    });
  }
  PENUMBRA_HD Moments sample(float level, vec3 world) const {
    float m[K];
    sample_lanes<ScalarLanes>(level, world, true, m);
    Moments r;
    for (int i = 0; i < K; ++i) r[i] = m[i];
    return r;
  }

 private:
  // glm::mix's form, a (1 - f) + b f, on any lane type.
  template <class F> PENUMBRA_HD PENUMBRA_FORCE_INLINE static F lerp(F a, F b, F f) { return a * (1.0f - f) + b * f; }
};

}  // namespace penumbra

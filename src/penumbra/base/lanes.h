#pragma once
// Lanes: how one kernel source runs on one ray or on a packet of rays
// (DESIGN.md 9). A per-sample kernel is a template over a lane type L that
// names
//   L::Float, L::Int (32-bit), L::Index (voxel offsets), L::Mask, L::Vec3, L::kWidth
// and uses ordinary arithmetic plus the free functions below (select, any,
// none, min, max, clamp, floor, sqrt, to_int, to_float, gather, ...).
//
// ScalarLanes, here, is plain float / int / bool / glm::vec3: the scalar CPU
// path and every CUDA thread see only this. SimdLanes (render/simd/
// simd_lanes.h, CPU only) is a Highway vector holding 8 or 16 rays; its types
// live in a namespace per instruction set and find the same free functions
// by argument-dependent lookup, so a kernel written against these names
// compiles for both.
//
// Control flow in a kernel is written with masks: `if (none(m)) continue;`
// skips work no lane needs, and results are merged with select(). With
// ScalarLanes a mask is a bool and select() folds away, so the scalar
// instantiation is the scalar code it replaced.
#include "penumbra/base/vec.h"

#include <cstdint>

namespace penumbra {

struct ScalarLanes {
  static constexpr int kWidth = 1;
  using Float = float;
  using Int = std::int32_t;
  using Index = std::int64_t;
  using Mask = bool;
  using Vec3 = vec3;

  PENUMBRA_HD static Float load(const float* p) { return *p; }
  PENUMBRA_HD static void store(Float v, float* p) { *p = v; }
  PENUMBRA_HD static Int load(const std::int32_t* p) { return *p; }
  PENUMBRA_HD static void store(Int v, std::int32_t* p) { *p = v; }
  // Bit i set when lane i is on.
  PENUMBRA_HD static std::uint32_t bits(Mask m) { return m ? 1u : 0u; }
  PENUMBRA_HD static Mask from_bits(std::uint32_t b) { return (b & 1u) != 0u; }
};

// ---- lane bit sets (bit i = lane i)
PENUMBRA_HD PENUMBRA_FORCE_INLINE int bit_count(std::uint32_t bits) {
#if defined(__CUDA_ARCH__)
  return __popc(bits);
#else
  return __builtin_popcount(bits);
#endif
}
// The lowest set bit of a non-zero set.
PENUMBRA_HD PENUMBRA_FORCE_INLINE int lowest_bit(std::uint32_t bits) {
#if defined(__CUDA_ARCH__)
  return __ffs(int(bits)) - 1;
#else
  return __builtin_ctz(bits);
#endif
}

// ---- masks
PENUMBRA_HD PENUMBRA_FORCE_INLINE bool any(bool m) { return m; }
PENUMBRA_HD PENUMBRA_FORCE_INLINE bool none(bool m) { return !m; }
PENUMBRA_HD PENUMBRA_FORCE_INLINE bool all(bool m) { return m; }
PENUMBRA_HD PENUMBRA_FORCE_INLINE int count_true(bool m) { return m ? 1 : 0; }

PENUMBRA_HD PENUMBRA_FORCE_INLINE float select(bool m, float a, float b) { return m ? a : b; }
PENUMBRA_HD PENUMBRA_FORCE_INLINE std::int32_t select(bool m, std::int32_t a, std::int32_t b) { return m ? a : b; }
PENUMBRA_HD PENUMBRA_FORCE_INLINE std::int64_t select(bool m, std::int64_t a, std::int64_t b) { return m ? a : b; }
PENUMBRA_HD PENUMBRA_FORCE_INLINE vec3 select(bool m, vec3 a, vec3 b) { return m ? a : b; }
PENUMBRA_HD PENUMBRA_FORCE_INLINE bool select(bool m, bool a, bool b) { return m ? a : b; }

// ---- float lanes (the same rounding as glm's scalar functions)
PENUMBRA_HD PENUMBRA_FORCE_INLINE float min(float a, float b) { return glm::min(a, b); }
PENUMBRA_HD PENUMBRA_FORCE_INLINE float max(float a, float b) { return glm::max(a, b); }
PENUMBRA_HD PENUMBRA_FORCE_INLINE float clamp(float x, float lo, float hi) { return glm::clamp(x, lo, hi); }
PENUMBRA_HD PENUMBRA_FORCE_INLINE float floor(float x) { return glm::floor(x); }
PENUMBRA_HD PENUMBRA_FORCE_INLINE float sqrt(float x) { return glm::sqrt(x); }
// Doubles keep their precision (these names would otherwise hide ::sqrt and
// ::floor inside namespace penumbra).
PENUMBRA_HD PENUMBRA_FORCE_INLINE double floor(double x) { return glm::floor(x); }
PENUMBRA_HD PENUMBRA_FORCE_INLINE double sqrt(double x) { return glm::sqrt(x); }
PENUMBRA_HD PENUMBRA_FORCE_INLINE bool finite(float x) { return is_finite(x); }

// ---- integer lanes
PENUMBRA_HD PENUMBRA_FORCE_INLINE std::int32_t min(std::int32_t a, std::int32_t b) { return a < b ? a : b; }
PENUMBRA_HD PENUMBRA_FORCE_INLINE std::int32_t max(std::int32_t a, std::int32_t b) { return a > b ? a : b; }
// Truncation toward zero, as int(x).
PENUMBRA_HD PENUMBRA_FORCE_INLINE std::int32_t to_int(float x) { return std::int32_t(x); }
PENUMBRA_HD PENUMBRA_FORCE_INLINE float to_float(std::int32_t i) { return float(i); }
// int(x) for 0 <= x < 2^22 (grid and table indices), which packets compute
// without the range fix-up a general conversion needs.
PENUMBRA_HD PENUMBRA_FORCE_INLINE std::int32_t to_int_nonnegative(float x) { return std::int32_t(x); }
PENUMBRA_HD PENUMBRA_FORCE_INLINE float float_from_bits(std::int32_t bits) {
  float f;
  __builtin_memcpy(&f, &bits, sizeof(f));
  return f;
}
PENUMBRA_HD PENUMBRA_FORCE_INLINE std::int32_t bits_of(float f) {
  std::int32_t bits;
  __builtin_memcpy(&bits, &f, sizeof(bits));
  return bits;
}

// ---- memory: base[index] per lane (a gather for packets). Lanes that are
// off must still hold an index that is safe to read.
template <class T> PENUMBRA_HD PENUMBRA_FORCE_INLINE T gather(const T* base, std::int64_t index) { return base[index]; }

// The four floats base[index .. index + 3] per lane (a texel of four values):
// plain loads here; for packets (simd_lanes.h) one 16-byte load per lane and a
// transpose instead of four gathers (cssm's taps: docs/PERFORMANCE.md).
PENUMBRA_HD PENUMBRA_FORCE_INLINE void gather4(const float* base, std::int64_t index, float& v0, float& v1, float& v2,
                                               float& v3) {
  v0 = base[index];
  v1 = base[index + 1];
  v2 = base[index + 2];
  v3 = base[index + 3];
}

// The voxel at `offset` as float, and the pair at `offset` and `offset +
// step`: plain loads here; gathers for packets (simd_lanes.h), where 8- and
// 16-bit voxels come from 32-bit words. `count` is the number of voxels
// behind `base`, which a word read must not pass.
template <class T>
PENUMBRA_HD PENUMBRA_FORCE_INLINE float load_voxel(const T* base, std::int64_t offset, std::int64_t /*count*/) {
  return float(base[offset]);
}
template <class T>
PENUMBRA_HD PENUMBRA_FORCE_INLINE void load_voxel_pair(const T* base, std::int64_t offset, std::int64_t step,
                                                        std::int64_t /*count*/, float& first, float& second) {
  first = float(base[offset]);
  second = float(base[offset + step]);
}

// The first three signed bytes of the 4-byte texel at `offset` (texel units),
// as floats (precomputed normals, normal_volume.h).
PENUMBRA_HD PENUMBRA_FORCE_INLINE vec3 load_texel_xyz(const std::int8_t* texels, std::int64_t offset) {
  const std::int8_t* c = texels + 4 * offset;
  return vec3(float(c[0]), float(c[1]), float(c[2]));
}
// The texels at `offset` and `offset + step` (see load_voxel_pair): plain loads
// here; for packets and step 1 both from one 64-bit gather (simd_lanes.h).
PENUMBRA_HD PENUMBRA_FORCE_INLINE void load_texel_pair_xyz(const std::int8_t* texels, std::int64_t offset,
                                                            std::int64_t step, vec3& first, vec3& second) {
  first = load_texel_xyz(texels, offset);
  second = load_texel_xyz(texels, offset + step);
}

// The first n lanes of a packet (1 <= n; all of them when n >= W): a row's
// last, partial packet.
template <class L> PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Mask first_lanes(int n) {
  return L::from_bits(n >= 32 ? ~0u : (1u << n) - 1u);
}

// Stores the first n lanes of v at p (all W when n >= W): a row's last packet
// must not write past the row, whose next entries may be another thread's.
template <class L> PENUMBRA_HD PENUMBRA_FORCE_INLINE void store_first(typename L::Float v, float* p, int n) {
  if (n >= L::kWidth) {
    L::store(v, p);
    return;
  }
  float lanes[L::kWidth];
  L::store(v, lanes);
  for (int i = 0; i < n; ++i) p[i] = lanes[i];
}

// Lane-generic helpers written once over L.
template <class L> using LaneFloat = typename L::Float;
template <class L> using LaneMask = typename L::Mask;
template <class L> using LaneVec3 = typename L::Vec3;

}  // namespace penumbra

#pragma once
// SimdLanes: the packet lane type of the CPU backend, a Highway vector of 16
// (AVX-512) or 8 (AVX2) floats, for the lane-generic kernels of lanes.h.
//
// This header is compiled only into the SIMD translation units that
// cmake/PenumbraSimd.cmake builds once per instruction set, each with that
// set's -m flags and HWY_COMPILE_ONLY_STATIC, so Highway's static target is
// the unit's target and every type here lives in a namespace of its own
// (penumbra::N_AVX3, penumbra::N_AVX2): the generic kernels instantiated with
// them get names no other unit uses. The wrappers exist so that kernels can
// mix packets and scalars (`x * 0.5f`) and find min, select, gather... by
// argument-dependent lookup, exactly as they find the scalar versions.
#if defined(__CUDACC__)
#error "simd_lanes.h is CPU only; CUDA kernels use ScalarLanes"
#endif
#if !defined(HWY_COMPILE_ONLY_STATIC) || !defined(PENUMBRA_SIMD_TARGET)
#error "simd_lanes.h belongs in a per-target SIMD unit (penumbra_simd_sources in cmake/PenumbraSimd.cmake)"
#endif

#include "penumbra/backends/cpu/packets.h"
#include "penumbra/base/lanes.h"
#include "penumbra/scene/light.h"

#include <hwy/highway.h>

#include <cstdint>

namespace penumbra {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

// The target this unit is built for.
inline constexpr SimdTarget kThisSimdTarget = SimdTarget::PENUMBRA_SIMD_TARGET;
static_assert((kThisSimdTarget == SimdTarget::Avx3 && HWY_TARGET == HWY_AVX3) ||
                  (kThisSimdTarget == SimdTarget::Avx2 && HWY_TARGET == HWY_AVX2),
              "the unit's -m flags and PENUMBRA_SIMD_TARGET disagree (cmake/PenumbraSimd.cmake)");

using FloatTag = hn::ScalableTag<float>;
using IntTag = hn::RebindToSigned<FloatTag>;
using UintTag = hn::RebindToUnsigned<FloatTag>;

struct MaskV {
  hn::Mask<FloatTag> m;
  MaskV() = default;
  HWY_INLINE MaskV(hn::Mask<FloatTag> x) : m(x) {}
  HWY_INLINE MaskV(bool b) : m(b ? hn::FirstN(FloatTag(), hn::Lanes(FloatTag())) : hn::FirstN(FloatTag(), 0)) {}
};

struct FloatV {
  hn::Vec<FloatTag> v;
  FloatV() = default;
  HWY_INLINE FloatV(hn::Vec<FloatTag> x) : v(x) {}
  HWY_INLINE FloatV(float s) : v(hn::Set(FloatTag(), s)) {}
};

struct IntV {
  hn::Vec<IntTag> v;
  IntV() = default;
  HWY_INLINE IntV(hn::Vec<IntTag> x) : v(x) {}
  HWY_INLINE IntV(std::int32_t s) : v(hn::Set(IntTag(), s)) {}
};

// ---- masks
HWY_INLINE MaskV operator&(MaskV a, MaskV b) { return hn::And(a.m, b.m); }
HWY_INLINE MaskV operator|(MaskV a, MaskV b) { return hn::Or(a.m, b.m); }
HWY_INLINE MaskV operator^(MaskV a, MaskV b) { return hn::Xor(a.m, b.m); }
HWY_INLINE MaskV operator!(MaskV a) { return hn::Not(a.m); }
HWY_INLINE MaskV operator==(MaskV a, MaskV b) { return hn::Not(hn::Xor(a.m, b.m)); }
HWY_INLINE MaskV& operator&=(MaskV& a, MaskV b) { return a = a & b; }
HWY_INLINE MaskV& operator|=(MaskV& a, MaskV b) { return a = a | b; }
HWY_INLINE MaskV select(MaskV m, MaskV a, MaskV b) { return hn::Or(hn::And(m.m, a.m), hn::AndNot(m.m, b.m)); }
HWY_INLINE bool any(MaskV a) { return !hn::AllFalse(FloatTag(), a.m); }
HWY_INLINE bool none(MaskV a) { return hn::AllFalse(FloatTag(), a.m); }
HWY_INLINE bool all(MaskV a) { return hn::AllTrue(FloatTag(), a.m); }
HWY_INLINE int count_true(MaskV a) { return int(hn::CountTrue(FloatTag(), a.m)); }

// ---- floats
HWY_INLINE FloatV operator+(FloatV a, FloatV b) { return hn::Add(a.v, b.v); }
HWY_INLINE FloatV operator-(FloatV a, FloatV b) { return hn::Sub(a.v, b.v); }
HWY_INLINE FloatV operator*(FloatV a, FloatV b) { return hn::Mul(a.v, b.v); }
HWY_INLINE FloatV operator/(FloatV a, FloatV b) { return hn::Div(a.v, b.v); }
HWY_INLINE FloatV operator-(FloatV a) { return hn::Neg(a.v); }
HWY_INLINE FloatV& operator+=(FloatV& a, FloatV b) { return a = a + b; }
HWY_INLINE FloatV& operator-=(FloatV& a, FloatV b) { return a = a - b; }
HWY_INLINE FloatV& operator*=(FloatV& a, FloatV b) { return a = a * b; }
HWY_INLINE FloatV& operator/=(FloatV& a, FloatV b) { return a = a / b; }
HWY_INLINE MaskV operator<(FloatV a, FloatV b) { return hn::Lt(a.v, b.v); }
HWY_INLINE MaskV operator>(FloatV a, FloatV b) { return hn::Gt(a.v, b.v); }
HWY_INLINE MaskV operator<=(FloatV a, FloatV b) { return hn::Le(a.v, b.v); }
HWY_INLINE MaskV operator>=(FloatV a, FloatV b) { return hn::Ge(a.v, b.v); }
HWY_INLINE MaskV operator==(FloatV a, FloatV b) { return hn::Eq(a.v, b.v); }
HWY_INLINE MaskV operator!=(FloatV a, FloatV b) { return hn::Ne(a.v, b.v); }

HWY_INLINE FloatV select(MaskV m, FloatV a, FloatV b) { return hn::IfThenElse(m.m, a.v, b.v); }
// glm::min(a, b) is (b < a) ? b : a and glm::max(a, b) (a < b) ? b : a. The
// units are x86 only (AVX2, AVX-512), whose MINPS(x, y) is (x < y) ? x : y
// and MAXPS(x, y) (x > y) ? x : y, and Highway maps Min/Max to them: with the
// arguments swapped one instruction gives glm's result exactly, NaN and -0
// included (lanes_test.cpp checks it).
static_assert(HWY_TARGET == HWY_AVX2 || HWY_TARGET == HWY_AVX3, "min/max rely on x86 MINPS/MAXPS operand order");
HWY_INLINE FloatV min(FloatV a, FloatV b) { return hn::Min(b.v, a.v); }
HWY_INLINE FloatV max(FloatV a, FloatV b) { return hn::Max(b.v, a.v); }
HWY_INLINE FloatV clamp(FloatV x, FloatV lo, FloatV hi) { return min(max(x, lo), hi); }
HWY_INLINE FloatV floor(FloatV x) { return hn::Floor(x.v); }
HWY_INLINE FloatV sqrt(FloatV x) { return hn::Sqrt(x.v); }
HWY_INLINE MaskV finite(FloatV x) { return hn::IsFinite(x.v); }

// ---- 32-bit integers
HWY_INLINE IntV operator+(IntV a, IntV b) { return hn::Add(a.v, b.v); }
HWY_INLINE IntV operator-(IntV a, IntV b) { return hn::Sub(a.v, b.v); }
HWY_INLINE IntV operator*(IntV a, IntV b) { return hn::Mul(a.v, b.v); }
HWY_INLINE IntV operator&(IntV a, IntV b) { return hn::And(a.v, b.v); }
HWY_INLINE IntV operator|(IntV a, IntV b) { return hn::Or(a.v, b.v); }
HWY_INLINE IntV& operator+=(IntV& a, IntV b) { return a = a + b; }
// Arithmetic shifts by a constant count (as int32 >> n and << n).
HWY_INLINE IntV operator>>(IntV a, int n) { return hn::ShiftRightSame(a.v, n); }
HWY_INLINE IntV operator<<(IntV a, int n) { return hn::ShiftLeftSame(a.v, n); }
HWY_INLINE MaskV operator<(IntV a, IntV b) { return hn::RebindMask(FloatTag(), hn::Lt(a.v, b.v)); }
HWY_INLINE MaskV operator>(IntV a, IntV b) { return hn::RebindMask(FloatTag(), hn::Gt(a.v, b.v)); }
HWY_INLINE MaskV operator<=(IntV a, IntV b) { return !(a > b); }
HWY_INLINE MaskV operator>=(IntV a, IntV b) { return !(a < b); }
HWY_INLINE MaskV operator==(IntV a, IntV b) { return hn::RebindMask(FloatTag(), hn::Eq(a.v, b.v)); }
HWY_INLINE IntV select(MaskV m, IntV a, IntV b) { return hn::IfThenElse(hn::RebindMask(IntTag(), m.m), a.v, b.v); }
HWY_INLINE IntV min(IntV a, IntV b) { return hn::Min(a.v, b.v); }
HWY_INLINE IntV max(IntV a, IntV b) { return hn::Max(a.v, b.v); }
HWY_INLINE IntV to_int(FloatV x) { return hn::ConvertTo(IntTag(), x.v); }
HWY_INLINE FloatV to_float(IntV i) { return hn::ConvertTo(FloatTag(), i.v); }
// floor(x) + 1.5 * 2^23 holds floor(x) in its low mantissa bits.
HWY_INLINE IntV to_int_nonnegative(FloatV x) {
  constexpr float bias = 12582912.0f;
  return hn::Sub(hn::BitCast(IntTag(), hn::Add(hn::Floor(x.v), hn::Set(FloatTag(), bias))),
                 hn::BitCast(IntTag(), hn::Set(FloatTag(), bias)));
}
HWY_INLINE FloatV float_from_bits(IntV bits) { return hn::BitCast(FloatTag(), bits.v); }
HWY_INLINE IntV bits_of(FloatV f) { return hn::BitCast(IntTag(), f.v); }

// ---- memory. Gathers read every lane: lanes that are off must hold a safe
// index (callers select 0 there); Highway 1.0.3 has no masked gather.
HWY_INLINE FloatV gather(const float* base, IntV index) { return hn::GatherIndex(FloatTag(), base, index.v); }
HWY_INLINE IntV gather(const std::int32_t* base, IntV index) { return hn::GatherIndex(IntTag(), base, index.v); }
// base[index + k] for k = 0..3 per lane (lanes.h): each lane's 16 bytes in one
// load into a buffer, then one de-interleaving load.
HWY_INLINE void gather4(const float* base, IntV index, FloatV& v0, FloatV& v1, FloatV& v2, FloatV& v3) {
  constexpr std::size_t kMax = hn::MaxLanes(FloatTag());
  const std::size_t n = hn::Lanes(FloatTag());
  HWY_ALIGN std::int32_t at[kMax];
  HWY_ALIGN float texels[4 * kMax];
  hn::Store(index.v, IntTag(), at);
  for (std::size_t i = 0; i < n; ++i) __builtin_memcpy(texels + 4 * i, base + at[i], 4 * sizeof(float));
  hn::LoadInterleaved4(FloatTag(), texels, v0.v, v1.v, v2.v, v3.v);
}
// The 32-bit word at a byte offset (unaligned).
HWY_INLINE IntV gather_word(const void* base, IntV byte_offset) {
  return hn::GatherOffset(IntTag(), static_cast<const std::int32_t*>(base), byte_offset.v);
}
// Logical right shift of each lane by its own count (0..31).
HWY_INLINE IntV shift_right_logical(IntV a, IntV counts) {
  return hn::BitCast(IntTag(), hn::Shr(hn::BitCast(UintTag(), a.v), hn::BitCast(UintTag(), counts.v)));
}

// One voxel per lane as float (see load_voxel in lanes.h). 8- and 16-bit
// voxels come from a 32-bit word read at the voxel, moved back where it would
// pass the end of the data (`count` voxels) and shifted into place.
template <class T> HWY_INLINE FloatV load_voxel(const T* base, IntV offset, std::int64_t count) {
  if constexpr (std::is_same_v<T, float>) {
    return hn::GatherIndex(FloatTag(), base, offset.v);
  } else if constexpr (sizeof(T) == 4) {
    static_assert(std::is_same_v<T, std::int32_t>, "32-bit voxels are float or int32 in packets");
    return to_float(IntV(hn::GatherIndex(IntTag(), base, offset.v)));
  } else {
    static_assert(sizeof(T) <= 2, "voxel types of 1, 2 or 4 bytes");
    constexpr int bits = 8 * int(sizeof(T));
    const std::int32_t last_word = std::int32_t(count * std::int64_t(sizeof(T))) - 4;
    const IntV byte_offset = offset * IntV(int(sizeof(T)));
    const IntV word_offset = min(byte_offset, IntV(last_word));
    const IntV word = shift_right_logical(gather_word(base, word_offset), (byte_offset - word_offset) << 3);
    return to_float(std::is_signed_v<T> ? (word << (32 - bits)) >> (32 - bits) : word & IntV((1 << bits) - 1));
  }
}

// The voxels at `offset` and `offset + step` (see lanes.h): for 8- and 16-bit
// voxels and step 1, both from one word.
template <class T>
HWY_INLINE void load_voxel_pair(const T* base, IntV offset, std::int64_t step, std::int64_t count, FloatV& first,
                                FloatV& second) {
  if constexpr (sizeof(T) <= 2) {
    if (step == 1) {
      constexpr int bits = 8 * int(sizeof(T));
      const std::int32_t last_word = std::int32_t(count * std::int64_t(sizeof(T))) - 4;
      const IntV byte_offset = offset * IntV(int(sizeof(T)));
      const IntV word_offset = min(byte_offset, IntV(last_word));
      const IntV word = shift_right_logical(gather_word(base, word_offset), (byte_offset - word_offset) << 3);
      if constexpr (std::is_signed_v<T>) {
        first = to_float((word << (32 - bits)) >> (32 - bits));
        second = to_float((word << (32 - 2 * bits)) >> (32 - bits));
      } else {
        first = to_float(word & IntV((1 << bits) - 1));
        second = to_float(shift_right_logical(word, IntV(bits)) & IntV((1 << bits) - 1));
      }
      return;
    }
  }
  first = load_voxel(base, offset, count);
  second = load_voxel(base, offset + IntV(std::int32_t(step)), count);
}

// ---- three-component packets
struct Vec3V {
  FloatV x, y, z;
  Vec3V() = default;
  HWY_INLINE Vec3V(FloatV a, FloatV b, FloatV c) : x(a), y(b), z(c) {}
  HWY_INLINE explicit Vec3V(FloatV s) : x(s), y(s), z(s) {}
  HWY_INLINE explicit Vec3V(float s) : x(s), y(s), z(s) {}
  HWY_INLINE Vec3V(vec3 u) : x(u.x), y(u.y), z(u.z) {}
  HWY_INLINE FloatV& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
  HWY_INLINE const FloatV& operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
};

HWY_INLINE Vec3V operator+(const Vec3V& a, const Vec3V& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
HWY_INLINE Vec3V operator-(const Vec3V& a, const Vec3V& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
HWY_INLINE Vec3V operator*(const Vec3V& a, const Vec3V& b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
HWY_INLINE Vec3V operator/(const Vec3V& a, const Vec3V& b) { return {a.x / b.x, a.y / b.y, a.z / b.z}; }
HWY_INLINE Vec3V operator*(const Vec3V& a, FloatV s) { return {a.x * s, a.y * s, a.z * s}; }
HWY_INLINE Vec3V operator*(FloatV s, const Vec3V& a) { return {s * a.x, s * a.y, s * a.z}; }
// One division for three (last-place rounding differs from three divisions).
HWY_INLINE Vec3V operator/(const Vec3V& a, FloatV s) {
  const FloatV r = FloatV(1.0f) / s;
  return {a.x * r, a.y * r, a.z * r};
}
HWY_INLINE Vec3V operator*(const Vec3V& a, float s) { return a * FloatV(s); }
HWY_INLINE Vec3V operator*(float s, const Vec3V& a) { return FloatV(s) * a; }
HWY_INLINE Vec3V operator-(const Vec3V& a) { return {-a.x, -a.y, -a.z}; }
HWY_INLINE Vec3V& operator+=(Vec3V& a, const Vec3V& b) { return a = a + b; }
HWY_INLINE Vec3V& operator*=(Vec3V& a, const Vec3V& b) { return a = a * b; }
HWY_INLINE FloatV dot(const Vec3V& a, const Vec3V& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
HWY_INLINE FloatV length(const Vec3V& a) { return sqrt(dot(a, a)); }
// glm::normalize multiplies by inversesqrt; the packet refines the
// processor's 14-bit estimate by one Newton step (relative error ~1e-7).
HWY_INLINE Vec3V normalize(const Vec3V& a) {
  const FloatV d = dot(a, a);
  const FloatV y = hn::ApproximateReciprocalSqrt(d.v);
  return a * (y * (FloatV(1.5f) - FloatV(0.5f) * d * y * y));
}
HWY_INLINE Vec3V cross(const Vec3V& a, const Vec3V& b) {
  return {a.y * b.z - b.y * a.z, a.z * b.x - b.z * a.x, a.x * b.y - b.x * a.y};
}
HWY_INLINE Vec3V min(const Vec3V& a, const Vec3V& b) { return {min(a.x, b.x), min(a.y, b.y), min(a.z, b.z)}; }
HWY_INLINE Vec3V max(const Vec3V& a, const Vec3V& b) { return {max(a.x, b.x), max(a.y, b.y), max(a.z, b.z)}; }
HWY_INLINE Vec3V clamp(const Vec3V& a, const Vec3V& lo, const Vec3V& hi) { return min(max(a, lo), hi); }
HWY_INLINE Vec3V select(MaskV m, const Vec3V& a, const Vec3V& b) {
  return {select(m, a.x, b.x), select(m, a.y, b.y), select(m, a.z, b.z)};
}

// Bytes 0, 1, 2 of the 4-byte texel at `offset` (texel units) as signed
// values (see lanes.h).
HWY_INLINE Vec3V texel_xyz(IntV word) {
  return Vec3V(to_float((word << 24) >> 24), to_float((word << 16) >> 24), to_float((word << 8) >> 24));
}
HWY_INLINE Vec3V load_texel_xyz(const std::int8_t* texels, IntV offset) {
  return texel_xyz(gather_word(texels, offset << 2));
}
// The texels at `offset` and `offset + step` (lanes.h). With step 1 they are
// the two halves of one 8-byte word: two 64-bit gathers (each over half the
// lanes) fetch what four 32-bit gathers of the same lanes would. offset + 1 is
// a texel of the grid wherever step is 1 (a cell's base is at most dims - 2).
HWY_INLINE void load_texel_pair_xyz(const std::int8_t* texels, IntV offset, std::int64_t step, Vec3V& first,
                                    Vec3V& second) {
  if (step != 1) {
    first = load_texel_xyz(texels, offset);
    second = load_texel_xyz(texels, offset + IntV(std::int32_t(step)));
    return;
  }
  const hn::Repartition<std::int64_t, IntTag> wide;
  const hn::Half<IntTag> half;
  const auto* words = reinterpret_cast<const std::int64_t*>(texels);
  const IntV bytes = offset << 2;
  const auto lower = hn::GatherOffset(wide, words, hn::PromoteTo(wide, hn::LowerHalf(half, bytes.v)));
  const auto upper = hn::GatherOffset(wide, words, hn::PromoteTo(wide, hn::UpperHalf(half, bytes.v)));
  // Little-endian: the even 32-bit halves are the texels at offset, the odd ones those after them.
  first = texel_xyz(IntV(hn::ConcatEven(IntTag(), hn::BitCast(IntTag(), upper), hn::BitCast(IntTag(), lower))));
  second = texel_xyz(IntV(hn::ConcatOdd(IntTag(), hn::BitCast(IntTag(), upper), hn::BitCast(IntTag(), lower))));
}

struct SimdLanes {
  static constexpr int kWidth = int(hn::MaxLanes(FloatTag()));
  using Float = FloatV;
  using Int = IntV;
  using Index = IntV;
  using Mask = MaskV;
  using Vec3 = Vec3V;

  static HWY_INLINE Float load(const float* p) { return hn::LoadU(FloatTag(), p); }
  static HWY_INLINE void store(Float v, float* p) { hn::StoreU(v.v, FloatTag(), p); }
  static HWY_INLINE Int load(const std::int32_t* p) { return hn::LoadU(IntTag(), p); }
  static HWY_INLINE void store(Int v, std::int32_t* p) { hn::StoreU(v.v, IntTag(), p); }
  static HWY_INLINE std::uint32_t bits(Mask m) {
    std::uint8_t bytes[8] = {};
    hn::StoreMaskBits(FloatTag(), m.m, bytes);
    return std::uint32_t(bytes[0]) | (std::uint32_t(bytes[1]) << 8);
  }
  static HWY_INLINE Mask from_bits(std::uint32_t b) {
    const std::uint8_t bytes[8] = {std::uint8_t(b), std::uint8_t(b >> 8)};
    return hn::LoadMaskBits(FloatTag(), bytes);
  }

  // A Visibility without a packet form (lighting.h), called lane by lane on
  // the active lanes; the others get 0.
  template <class Visibility>
  static HWY_INLINE Vec3V scalarize(const Visibility& visibility, int light, const Vec3V& p,
                                    const LightSampleL<SimdLanes>& ls, Mask active) {
    constexpr int W = kWidth;
    float px[W], py[W], pz[W], lx[W], ly[W], lz[W], distance[W], rx[W], ry[W], rz[W];
    store(p.x, px), store(p.y, py), store(p.z, pz);
    store(ls.to_light.x, lx), store(ls.to_light.y, ly), store(ls.to_light.z, lz);
    store(ls.distance, distance);
    store(ls.radiance.x, rx), store(ls.radiance.y, ry), store(ls.radiance.z, rz);
    float ox[W] = {}, oy[W] = {}, oz[W] = {};
    for (std::uint32_t todo = bits(active); todo != 0; todo &= todo - 1) {
      const int i = lowest_bit(todo);
      const vec3 r = visibility(light, vec3(px[i], py[i], pz[i]),
                                LightSample{vec3(lx[i], ly[i], lz[i]), distance[i], vec3(rx[i], ry[i], rz[i])});
      ox[i] = r.x;
      oy[i] = r.y;
      oz[i] = r.z;
    }
    return Vec3V(load(ox), load(oy), load(oz));
  }
};

}  // namespace HWY_NAMESPACE
}  // namespace penumbra

#pragma once
// Numeric helpers shared by host and kernel code: the vector types (vec.h)
// and exp, log and pow written once over a lane's float type F (a float, or
// a packet of floats, see lanes.h), so the scalar, SIMD and CUDA paths round
// alike.
#include "penumbra/base/lanes.h"
#include "penumbra/base/vec.h"

namespace penumbra {

// exp(x) for x <= 0, inlined and branch-light for per-sample opacity and
// transmittance: x = n ln2 + f with n an integer (built into the exponent
// bits) and |f| <= ln2 / 2, f computed with a two-part ln2 (Cody & Waite) and
// e^f by its Taylor series to degree 6 (relative error < 3e-7). Returns 0
// below the float range. Rounding to the nearest integer adds and subtracts
// 1.5 * 2^23 (penumbra never builds with -ffast-math, which would fold it).
template <class F> PENUMBRA_HD PENUMBRA_FORCE_INLINE F exp_nonpositive(F x) {
  const auto in_range = x > -87.0f;
  if (none(in_range)) return F(0.0f);
  x = select(in_range, x, F(0.0f));
  constexpr float round_bias = 12582912.0f;
  const F n = (x * 1.44269504088896341f + round_bias) - round_bias;
  const F f = (x - n * 0.693145751953125f) - n * 1.428606765330187045e-06f;
  const F p =
      1.0f + f * (1.0f + f * (0.5f + f * (1.0f / 6.0f + f * (1.0f / 24.0f + f * (1.0f / 120.0f + f * (1.0f / 720.0f))))));
  const F scale = float_from_bits((to_int(n) + 127) << 23);
  return select(in_range, p * scale, F(0.0f));
}

// x = m 2^e with m in [sqrt(1/2), sqrt(2)) for finite x > 0: returns ln(m) =
// 2 atanh(z), z = (m - 1) / (m + 1) (|z| < 0.172), from its odd series, and
// sets e. log_positive and log2_positive below.
template <class F> PENUMBRA_HD PENUMBRA_FORCE_INLINE F log_mantissa(F x, F& exponent) {
  const auto bits = bits_of(x);
  auto e = ((bits >> 23) & 0xff) - 127;
  F m = float_from_bits((bits & 0x007fffff) | 0x3f800000);  // m in [1, 2)
  const auto high = m > 1.41421356f;
  m = select(high, m * 0.5f, m);
  e = select(high, e + 1, e);
  exponent = to_float(e);
  const F z = (m - 1.0f) / (m + 1.0f);
  const F z2 = z * z;
  return 2.0f * z * (1.0f + z2 * (1.0f / 3.0f + z2 * (1.0f / 5.0f + z2 * (1.0f / 7.0f + z2 * (1.0f / 9.0f)))));
}

// ln(x) for finite x > 0, to about 2e-7 relative. Inline and branch-free for
// the shading kernels.
template <class F> PENUMBRA_HD PENUMBRA_FORCE_INLINE F log_positive(F x) {
  F exponent;
  const F series = log_mantissa(x, exponent);
  return exponent * 0.693147180559945f + series;
}

// log2(x) for finite x > 0, with the exponent kept exact, so a power of two
// gives its exponent exactly.
template <class F> PENUMBRA_HD PENUMBRA_FORCE_INLINE F log2_positive(F x) {
  F exponent;
  const F series = log_mantissa(x, exponent);
  return exponent + series * 1.44269504088896341f;
}

// 2^x for x >= 0 below 128: the whole part built into the exponent bits, the
// fraction through exp_nonpositive (2^f = 2 e^((f - 1) ln 2)).
template <class F> PENUMBRA_HD PENUMBRA_FORCE_INLINE F exp2_nonnegative(F x) {
  const auto whole = to_int(x);  // truncation: x >= 0
  const F fraction = x - to_float(whole);
  const F power = float_from_bits((whole + 127) << 23);
  return select(fraction > 0.0f, power * (2.0f * exp_nonpositive((fraction - 1.0f) * 0.693147180559945f)), power);
}

// erfc(x): the Chebyshev fit of t exp(-x^2 + P(t)), t = 1 / (1 + |x| / 2),
// of Press et al., Numerical Recipes in C, 2nd ed., section 6.2 (their erfcc;
// the coefficients are theirs; 1.2e-7 relative in exact arithmetic), and
// erfc(-x) = 2 - erfc(x). In float: within 1e-6 relative up to |x| = 4, and
// about x^2 6e-8 beyond (the rounding of x^2 in the exponent; Math tests). Inline and branch-free, for
// occlusion-map's per-step shares on every lane type.
template <class F> PENUMBRA_HD PENUMBRA_FORCE_INLINE F erfc_lanes(F x) {
  const F z = max(x, -x);
  const F t = 1.0f / (1.0f + 0.5f * z);
  F p = 0.17087277f;
  p = -0.82215223f + t * p;
  p = 1.48851587f + t * p;
  p = -1.13520398f + t * p;
  p = 0.27886807f + t * p;
  p = -0.18628806f + t * p;
  p = 0.09678418f + t * p;
  p = 0.37409196f + t * p;
  p = 1.00002368f + t * p;
  p = -1.26551223f + t * p;  // Horner, highest coefficient first
  const F tail = t * exp_nonpositive(min(p - z * z, F(0.0f)));
  return select(x >= 0.0f, tail, 2.0f - tail);
}

// x^s for x in [0, 1] and s >= 0 (a specular highlight); 0^s = 0 for s > 0
// and x^0 = 1. A whole s up to 256 (the usual shininess) takes repeated
// squaring, at most 16 products in place of a log and an exp; a power below
// 2^-120 reads 0 (as exp_nonpositive does below e^-87), so that no product is
// subnormal: each partial power is at least the whole one. Other s go
// through exp_nonpositive(s ln x).
template <class F> PENUMBRA_HD PENUMBRA_FORCE_INLINE F pow_unit(F x, float s) {
  if (s >= 1.0f && s <= 256.0f && s == float(int(s))) {
    const float smallest = exp_nonpositive(-83.1776617f / s);  // 2^(-120 / s)
    F base = select(x >= smallest, min(x, F(1.0f)), F(0.0f));
    F result(1.0f);
    for (unsigned n = unsigned(s);; base = base * base) {
      if (n & 1u) result = result * base;
      n >>= 1;
      if (n == 0) return result;
    }
  }
  const auto positive = x > 0.0f;
  const F zero_power(s > 0.0f ? 0.0f : 1.0f);
  if (none(positive)) return zero_power;
  const F safe = select(positive, x, F(1.0f));
  return select(positive, exp_nonpositive(F(s) * min(log_positive(safe), F(0.0f))), zero_power);
}

}  // namespace penumbra

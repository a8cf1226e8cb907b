#pragma once
// Vector types and small numeric helpers shared by host and kernel code.
#include "penumbra/base/hd.h"

#define GLM_FORCE_CTOR_INIT
#include <glm/glm.hpp>

#include <cstdint>
#include <limits>

namespace penumbra {

using glm::dvec3;
using glm::ivec2;
using glm::ivec3;
using glm::mat3;
using glm::mat4;
using glm::vec2;
using glm::vec3;
using glm::vec4;

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr float kInfinity = std::numeric_limits<float>::infinity();

PENUMBRA_HD inline float clamp01(float x) { return x < 0.0f ? 0.0f : (x > 1.0f ? 1.0f : x); }

// True for every float that is neither NaN nor +-infinity.
PENUMBRA_HD inline bool is_finite(float x) { return x - x == 0.0f; }

PENUMBRA_HD inline float max_component(vec3 v) { return glm::max(v.x, glm::max(v.y, v.z)); }
PENUMBRA_HD inline float min_component(vec3 v) { return glm::min(v.x, glm::min(v.y, v.z)); }

// exp(x) for x <= 0, inlined and branch-light for per-sample opacity and
// transmittance: x = n ln2 + f with n an integer (built into the exponent
// bits) and |f| <= ln2 / 2, f computed with a two-part ln2 (Cody & Waite) and
// e^f by its Taylor series to degree 6 (relative error < 3e-7). Returns 0
// below the float range. Rounding to the nearest integer adds and subtracts
// 1.5 * 2^23 (penumbra never builds with -ffast-math, which would fold it).
PENUMBRA_HD PENUMBRA_FORCE_INLINE float exp_nonpositive(float x) {
  if (!(x > -87.0f)) return 0.0f;
  constexpr float round_bias = 12582912.0f;
  const float n = (x * 1.44269504088896341f + round_bias) - round_bias;
  const float f = (x - n * 0.693145751953125f) - n * 1.428606765330187045e-06f;
  const float p =
      1.0f + f * (1.0f + f * (0.5f + f * (1.0f / 6.0f + f * (1.0f / 24.0f + f * (1.0f / 120.0f + f * (1.0f / 720.0f))))));
  const std::int32_t bits = (std::int32_t(n) + 127) << 23;
  float scale;
  __builtin_memcpy(&scale, &bits, sizeof(scale));
  return p * scale;
}

// ln(x) for finite x > 0, to about 2e-7 relative: x = m 2^e with m in
// [sqrt(1/2), sqrt(2)), ln(m) = 2 atanh(z), z = (m - 1) / (m + 1) (|z| < 0.172),
// from its odd series. Inline and branch-free for the shading kernels.
PENUMBRA_HD PENUMBRA_FORCE_INLINE float log_positive(float x) {
  std::int32_t bits;
  __builtin_memcpy(&bits, &x, sizeof(bits));
  std::int32_t e = ((bits >> 23) & 0xff) - 127;
  std::int32_t mbits = (bits & 0x007fffff) | 0x3f800000;  // m in [1, 2)
  float m;
  __builtin_memcpy(&m, &mbits, sizeof(m));
  if (m > 1.41421356f) {
    m *= 0.5f;
    e += 1;
  }
  const float z = (m - 1.0f) / (m + 1.0f);
  const float z2 = z * z;
  const float series = 2.0f * z * (1.0f + z2 * (1.0f / 3.0f + z2 * (1.0f / 5.0f + z2 * (1.0f / 7.0f + z2 * (1.0f / 9.0f)))));
  return float(e) * 0.693147180559945f + series;
}

// x^s for x in [0, 1] and s >= 0 (a specular highlight), through
// exp_nonpositive(s ln x); 0^s = 0 for s > 0 and x^0 = 1.
PENUMBRA_HD PENUMBRA_FORCE_INLINE float pow_unit(float x, float s) {
  if (!(x > 0.0f)) return s > 0.0f ? 0.0f : 1.0f;
  return exp_nonpositive(s * glm::min(log_positive(x), 0.0f));
}

// Rec. 709 / sRGB luminance of a linear colour.
PENUMBRA_HD inline float luminance(vec3 c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

}  // namespace penumbra

#pragma once
// Conversions from floating point that are defined for every input. A C++
// cast of a NaN, an infinity or a value outside the target's range (1e30 to
// int, 1e300 to float) is undefined behaviour; readers, scene values and
// render sizes go through these instead and report the value as an error.
// Host code only (they return std::optional).
#include <cmath>
#include <concepts>
#include <cstdint>
#include <limits>
#include <optional>

namespace penumbra {

// `v` truncated toward zero as an I, or nullopt when v is NaN, infinite or
// outside I's range.
template <std::integral I> std::optional<I> to_integer(double v) {
  // 2^digits is exact in a double for every integer type, and so are the
  // bounds below: v must lie in [min, max + 1) after truncation.
  constexpr double hi = 2.0 * double(std::uint64_t(1) << (std::numeric_limits<I>::digits - 1));
  constexpr double lo = std::numeric_limits<I>::is_signed ? -hi : 0.0;
  if (!(v > lo - 1.0 && v < hi)) return std::nullopt;  // NaN fails both
  return static_cast<I>(v);
}

// The same, but only for a v that is a whole number ("3", not "3.5").
template <std::integral I> std::optional<I> to_exact_integer(double v) {
  if (!(v == std::trunc(v))) return std::nullopt;
  return to_integer<I>(v);
}

// `v` as a float, or nullopt when it is finite but beyond the float range
// (NaN and infinities convert as they are).
inline std::optional<float> to_float(double v) {
  if (std::isfinite(v) && std::abs(v) > double(std::numeric_limits<float>::max())) return std::nullopt;
  return static_cast<float>(v);
}

}  // namespace penumbra

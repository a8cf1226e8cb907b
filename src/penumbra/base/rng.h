#pragma once
// PCG32 (O'Neill 2014, "PCG: A Family of Simple Fast Space-Efficient
// Statistically Good Algorithms for Random Number Generation"): 64-bit LCG state,
// xorshift-high + random-rotation output. Small, fast and reproducible on any
// backend, so per-pixel seeds give the same image on CPU and GPU.
#include "penumbra/base/hd.h"

#include <cstdint>

namespace penumbra {

class Pcg32 {
 public:
  PENUMBRA_HD Pcg32() { seed(0x853c49e6748fea9bULL, 0xda3e39cb94b95bdbULL); }
  PENUMBRA_HD explicit Pcg32(std::uint64_t sequence, std::uint64_t offset = 0x853c49e6748fea9bULL) {
    seed(offset, sequence);
  }

  PENUMBRA_HD void seed(std::uint64_t initial_state, std::uint64_t sequence) {
    state_ = 0u;
    increment_ = (sequence << 1u) | 1u;
    next_uint();
    state_ += initial_state;
    next_uint();
  }

  PENUMBRA_HD std::uint32_t next_uint() {
    const std::uint64_t old = state_;
    state_ = old * kMultiplier + increment_;
    const auto xorshifted = static_cast<std::uint32_t>(((old >> 18u) ^ old) >> 27u);
    const auto rotation = static_cast<std::uint32_t>(old >> 59u);
    return (xorshifted >> rotation) | (xorshifted << ((0u - rotation) & 31u));
  }

  // Uniform in [0, 1): the top 24 bits, so the result is never rounded up to 1.
  PENUMBRA_HD float next_float() { return static_cast<float>(next_uint() >> 8) * (1.0f / 16777216.0f); }

 private:
  static constexpr std::uint64_t kMultiplier = 6364136223846793005ULL;
  std::uint64_t state_;
  std::uint64_t increment_;
};

// A well-mixed 64-bit hash (the splitmix64 finaliser) for deriving seeds from
// pixel coordinates and frame numbers.
PENUMBRA_HD inline std::uint64_t mix_bits(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

}  // namespace penumbra

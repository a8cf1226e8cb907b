#include "penumbra/scene/volumetric_detail.h"

#include "penumbra/base/rng.h"

#include <numeric>

namespace penumbra {

NoiseTable make_noise_table(std::uint64_t seed) {
  std::array<std::uint8_t, 256> p{};
  std::iota(p.begin(), p.end(), std::uint8_t(0));
  Pcg32 rng(mix_bits(seed + 0x6e6f697365ULL));
  for (int i = 255; i > 0; --i) std::swap(p[std::size_t(i)], p[rng.next_uint() % std::uint32_t(i + 1)]);
  NoiseTable t;
  for (int i = 0; i < 512; ++i) t.perm[std::size_t(i)] = p[std::size_t(i & 255)];
  return t;
}

}  // namespace penumbra

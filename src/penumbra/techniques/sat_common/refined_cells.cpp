#include "penumbra/techniques/sat_common/refined_cells.h"

#include "penumbra/base/memory_budget.h"

#include <algorithm>

namespace penumbra {

void RefinedCells::plan(const Volume& cache, float tolerance, int refine) {
  clear();
  const ivec3 dims = cache.dims();
  const ivec3 cells = glm::max(dims - 1, ivec3(1));
  const ivec3 blocks = (cells + 3) / 4;
  const std::size_t block_count = std::size_t(blocks.x) * blocks.y * blocks.z;
  masks_.assign(block_count, 0);
  first_.assign(block_count, 0);
  const float* texels = cache.frame_as<float>(0);
  auto at = [&](int x, int y, int z) {
    return texels[std::size_t(x) + std::size_t(dims.x) * (std::size_t(y) + std::size_t(dims.y) * z)];
  };
  parallel_for(0, std::int64_t(block_count), [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t block = first; block < last; ++block) {
      const ivec3 b(int(block % blocks.x), int(block / blocks.x % blocks.y), int(block / blocks.x / blocks.y));
      std::uint64_t mask = 0;
      for (int bit = 0; bit < 64; ++bit) {
        const ivec3 c = b * 4 + ivec3(bit & 3, (bit >> 2) & 3, bit >> 4);
        if (c.x >= cells.x || c.y >= cells.y || c.z >= cells.z) continue;
        const ivec3 c1 = glm::min(c + 1, dims - 1);
        float lo = at(c.x, c.y, c.z), hi = lo;
        for (int k = 1; k < 8; ++k) {
          const float v = at(k & 1 ? c1.x : c.x, k & 2 ? c1.y : c.y, k & 4 ? c1.z : c.z);
          lo = std::min(lo, v);
          hi = std::max(hi, v);
        }
        if (hi - lo > tolerance) mask |= std::uint64_t(1) << bit;
      }
      masks_[std::size_t(block)] = mask;
    }
  });
  view_.cells = cells;
  view_.blocks = blocks;
  view_.refine = refine;
}

void RefinedCells::allocate(int refine) {
  std::size_t total = 0;
  for (std::size_t block = 0; block < masks_.size(); ++block) {
    first_[block] = std::uint32_t(total);
    total += std::size_t(popcount64(masks_[block]));
  }
  const std::size_t n = std::size_t(refine);
  check_memory_budget("the shadow cache's refined cells",
                      checked_product({std::uint64_t(total), n * n * n, sizeof(std::uint16_t)}));
  texels_.assign(total * n * n * n, 0);
  brick_count_ = total;
  view_.bricks = std::uint32_t(total);
}

void RefinedCells::clear() {
  first_.clear();
  first_.shrink_to_fit();
  masks_.clear();
  masks_.shrink_to_fit();
  texels_.clear();
  texels_.shrink_to_fit();
  brick_count_ = 0;
  view_ = RefinedCellsView{};
}

std::uint64_t RefinedCells::bytes() const {
  return first_.size() * sizeof(std::uint32_t) + masks_.size() * sizeof(std::uint64_t) +
         texels_.size() * sizeof(std::uint16_t);
}

}  // namespace penumbra

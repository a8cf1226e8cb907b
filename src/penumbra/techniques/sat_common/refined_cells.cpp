#include "penumbra/techniques/sat_common/refined_cells.h"

#include "penumbra/base/memory_budget.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace penumbra {

const float* brick_depth_table() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> depths{};
    depths[0] = kBrickMaxDepth;
    for (int code = 1; code < 256; ++code) depths[std::size_t(code)] = float(3.0 * std::log(255.0 / code));
    return depths;
  }();
  return table.data();
}

void RefinedCells::plan(const Volume& cache, float tolerance, int refine) {
  clear();
  const ivec3 dims = cache.dims();
  const ivec3 cells = glm::max(dims - 1, ivec3(1));
  const ivec3 blocks = (cells + 3) / 4;
  const std::size_t block_count = std::size_t(blocks.x) * blocks.y * blocks.z;
  std::vector<std::uint64_t>& masks = masks_[0];
  masks.assign(block_count, 0);
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
      masks[std::size_t(block)] = mask;
    }
  });
  view_.cells = cells;
  view_.blocks = blocks;
  // 2, 4, ... up to refine (and refine itself where it is odd).
  int count = 0;
  for (int r = 2; r < refine && count + 1 < RefinedCellsView::kMaxLevels; r += 2) view_.level[count++].refine = r;
  view_.level[count++].refine = refine;
  view_.levels = count;
  view_.depth_of_code = brick_depth_table();
}

std::vector<vec3> RefinedCells::check_points(int n) {
  std::vector<vec3> points;
  for (int z = 1; z < n; ++z)
    for (int y = 1; y < n; ++y)
      for (int x = 1; x < n; ++x) points.push_back(vec3(float(x), float(y), float(z)) / float(n));
  for (int axis = 0; axis < 3; ++axis) {
    for (const float side : {0.0f, 1.0f}) {
      vec3 f(0.5f);
      f[axis] = side;
      points.push_back(f);
    }
  }
  return points;
}

void RefinedCells::store(int l, const std::vector<std::int64_t>& cells, const std::vector<std::uint8_t>& keep,
                         const std::vector<std::uint8_t>& texels) {
  BrickLevelView& level = view_.level[l];
  const std::size_t blocks = std::size_t(view_.blocks.x) * view_.blocks.y * view_.blocks.z;
  const std::size_t per_brick = std::size_t(level.refine) * level.refine * level.refine;
  std::vector<std::uint64_t>& masks = masks_[l];
  masks.assign(blocks, 0);  // (level 0's masks held the candidates)
  std::size_t total = 0;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (!keep[i]) continue;
    masks[std::size_t(cells[i] / 64)] |= std::uint64_t(1) << (cells[i] % 64);
    ++total;
  }
  check_memory_budget("the shadow cache's refined cells",
                      checked_product({std::uint64_t(total), per_brick, sizeof(std::uint8_t)}));
  first_[l].assign(blocks, 0);
  std::size_t before = 0;
  for (std::size_t block = 0; block < blocks; ++block) {
    first_[l][block] = std::uint32_t(before);
    before += std::size_t(popcount64(masks[block]));
  }
  // The cells are in block and bit order, so the kept ones are in brick order.
  texels_[l].resize(total * per_brick);
  std::size_t brick = 0;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (!keep[i]) continue;
    std::copy_n(texels.begin() + std::ptrdiff_t(i * per_brick), per_brick,
                texels_[l].begin() + std::ptrdiff_t(brick * per_brick));
    ++brick;
  }
  level.bricks = std::uint32_t(total);
  if (total == 0) {  // an empty level keeps no masks (sample() skips it)
    std::vector<std::uint32_t>().swap(first_[l]);
    std::vector<std::uint64_t>().swap(masks);
  }
  level.block_first = first_[l].data();
  level.block_mask = masks.data();
  level.texels = texels_[l].data();
}

void RefinedCells::clear() {
  for (int l = 0; l < RefinedCellsView::kMaxLevels; ++l) {
    std::vector<std::uint32_t>().swap(first_[l]);
    std::vector<std::uint64_t>().swap(masks_[l]);
    std::vector<std::uint8_t>().swap(texels_[l]);
  }
  view_ = RefinedCellsView{};
}

std::size_t RefinedCells::brick_count() const {
  std::size_t total = 0;
  for (int l = 0; l < view_.levels; ++l) total += view_.level[l].bricks;
  return total;
}

std::uint64_t RefinedCells::bytes() const {
  std::uint64_t total = 0;
  for (int l = 0; l < RefinedCellsView::kMaxLevels; ++l) {
    total += first_[l].size() * sizeof(std::uint32_t) + masks_[l].size() * sizeof(std::uint64_t) +
             texels_[l].size() * sizeof(std::uint8_t);
  }
  return total;
}

}  // namespace penumbra

#pragma once
// Refined cells of a shadow cache (issue 22): for each cache cell whose eight
// texels differ by more than a tolerance (where the visibility jumps, at lit
// surfaces and sharp shadow edges) and whose trilinear read misses the
// visibility at a probe, a brick of refine^3 texels at the centres of the
// cell's refine^3 sub-cells, so that rendering there reads a fine sample
// instead of the light tables. The tables can then be released once the
// cache and its bricks are filled.
//
// A brick's read is trilinear between its own texels only, extrapolated
// linearly over the half sub-cell between its outer texels and the cell's
// faces (so refine >= 2). Texel-centred bricks hold refine^3 texels where
// bricks on the cell's corners need (refine + 1)^3 (2.4x more at refine 3):
// on the engine CT, centred refine 3 reads closer to the tables than corner
// bricks of refine 3 (docs/filtered-sat.md, "Memory").
//
// Texels hold the optical depth tau (visibility = exp(-tau)) in 16-bit fixed
// point over [0, kMaxDepth] (step 2.4e-4, a relative visibility error below
// 1.3e-4; tau beyond kMaxDepth reads as kMaxDepth, visibility < 1.2e-7).
// Interpolating the depth rather than the visibility follows what lit
// surfaces hold: inside a material the depth grows about linearly with the
// distance from its surface while the visibility falls exponentially.
//
// Storage is sparse: the cells are grouped in blocks of 4^3; each block keeps
// a 64-bit mask of the cells that have a brick and the index of its first
// brick, so a cell's brick is block_first + popcount(mask below its bit).
#include "penumbra/base/math.h"
#include "penumbra/base/memory_budget.h"
#include "penumbra/base/parallel.h"
#include "penumbra/base/vec.h"
#include "penumbra/techniques/sat_common/batch.h"
#include "penumbra/volume/volume.h"
#include "penumbra/volume/volume_view.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace penumbra {

PENUMBRA_HD inline int popcount64(std::uint64_t bits) {
#if defined(__CUDA_ARCH__)
  return __popcll(bits);
#else
  return __builtin_popcountll(bits);
#endif
}

struct RefinedCellsView {
  static constexpr float kMaxDepth = 16.0f;
  ivec3 cells{0};   // cache cells per axis (cache dims - 1)
  ivec3 blocks{0};  // blocks of 4^3 cells per axis
  int refine = 0;   // brick texels per cell edge (>= 2); 0: no bricks
  std::uint32_t bricks = 0;
  const std::uint32_t* block_first = nullptr;  // per block
  const std::uint64_t* block_mask = nullptr;   // per block
  const std::uint16_t* texels = nullptr;       // bricks of refine^3 depth texels, x fastest

  // The brick's visibility at `world` into `value`: exp of the depth
  // interpolated in the brick; false where the cell holding `world`
  // (clamped to the cache, as its trilinear read) has no brick.
  PENUMBRA_HD bool sample(const VolumeView& cache, vec3 world, float& value) const {
    if (refine <= 0) return false;
    const vec3 g = glm::clamp((world - cache.origin) / cache.spacing, vec3(0.0f), vec3(cells));
    const ivec3 c = glm::min(ivec3(g), cells - 1);
    const ivec3 b = c >> 2;
    const int block = b.x + blocks.x * (b.y + blocks.y * b.z);
    const int bit = (c.x & 3) + 4 * (c.y & 3) + 16 * (c.z & 3);
    const std::uint64_t mask = block_mask[block];
    if (((mask >> bit) & 1u) == 0) return false;
    const std::uint64_t below = mask & ((std::uint64_t(1) << bit) - 1u);
    const int n = refine;
    const std::uint16_t* t =
        texels + (std::size_t(block_first[block]) + std::size_t(popcount64(below))) * std::size_t(n * n * n);
    // Sub-cell coordinates with texel i at i; the outer half sub-cells
    // extrapolate from the two outermost texels.
    const vec3 s = (g - vec3(c)) * float(n) - 0.5f;
    const ivec3 s0 = glm::clamp(ivec3(glm::floor(s)), ivec3(0), ivec3(n - 2));
    const int sy = n, sz = n * n;
    auto lerp = [](float a, float b, float w) { return a + w * (b - a); };
    auto trilinear = [&](ivec3 base) {
      const vec3 f = s - vec3(base);
      const std::uint16_t* p = t + base.x + sy * base.y + sz * base.z;
      const float x00 = lerp(p[0], p[1], f.x), x10 = lerp(p[sy], p[sy + 1], f.x);
      const float x01 = lerp(p[sz], p[sz + 1], f.x), x11 = lerp(p[sz + sy], p[sz + sy + 1], f.x);
      return lerp(lerp(x00, x10, f.y), lerp(x01, x11, f.y), f.z);
    };
    const float depth = trilinear(s0) * (kMaxDepth / 65535.0f);
    value = exp_nonpositive(-glm::max(depth, 0.0f));
    return true;
  }
};

class RefinedCells {
 public:
  // Bricks of refine^3 texels (refine >= 2) for the cells of `cache` (a
  // float visibility grid from build_visibility_cache) whose texels differ
  // by more than `tolerance` and where the cache's trilinear read is off by
  // more than `probe_tolerance` from the visibility exp(-depth(world)) at
  // one of seven probes (the cell's centre and its faces' centres; a smooth
  // ramp across a penumbra needs no brick), filled with depth(world), the
  // optical depth toward the light. Throws OutOfMemoryBudget before
  // allocating bricks that do not fit.
  // `depth` may also be a batch (sat_common/batch.h): the probes are
  // evaluated as one batch, then the bricks' texels as another.
  template <class Depth>
  void build(const Volume& cache, float tolerance, float probe_tolerance, int refine, const Depth& depth) {
    plan(cache, tolerance, refine);
    const VolumeView view = cache.view();
    const float* data = cache.frame_as<float>(0);
    const ivec3 dims = cache.dims();
    const ivec3 blocks = view_.blocks;
    const std::int64_t block_count = std::int64_t(blocks.x) * blocks.y * blocks.z;
    auto cell_of = [&](std::int64_t block, int bit) {
      const ivec3 b(int(block % blocks.x), int(block / blocks.x % blocks.y), int(block / blocks.x / blocks.y));
      return b * 4 + ivec3(bit & 3, (bit >> 2) & 3, bit >> 4);
    };
    // The candidates, in block and bit order.
    std::vector<std::int64_t> candidates;  // block * 64 + bit
    for (std::int64_t block = 0; block < block_count; ++block) {
      for (std::uint64_t mask = masks_[std::size_t(block)]; mask != 0; mask &= mask - 1) {
        candidates.push_back(block * 64 + __builtin_ctzll(mask));
      }
    }
    static constexpr float kProbes[7][3] = {{0.5f, 0.5f, 0.5f}, {0.0f, 0.5f, 0.5f}, {1.0f, 0.5f, 0.5f},
                                            {0.5f, 0.0f, 0.5f}, {0.5f, 1.0f, 0.5f}, {0.5f, 0.5f, 0.0f},
                                            {0.5f, 0.5f, 1.0f}};
    // The probes' depths, then the bricks' texels in float, live only here.
    check_memory_budget("the shadow cache's refined cells: their probes",
                        checked_product({std::uint64_t(candidates.size()), 7 * sizeof(float) + 1}));
    std::vector<float> probe_depth(candidates.size() * 7);
    evaluate_batch(
        depth, std::int64_t(probe_depth.size()),
        [&](std::int64_t t) {
          const std::int64_t c = candidates[std::size_t(t / 7)];
          const float* f = kProbes[t % 7];
          return view.world_from_index(vec3(cell_of(c / 64, int(c % 64))) + vec3(f[0], f[1], f[2]));
        },
        probe_depth.data());
    // Keep the candidates whose trilinear read misses a probe (decided in
    // parallel, then set in the masks).
    std::vector<std::uint8_t> keep(candidates.size(), 0);
    parallel_for(0, std::int64_t(candidates.size()), [&](std::int64_t first, std::int64_t last) {
      for (std::int64_t n = first; n < last; ++n) {
        const ivec3 c = cell_of(candidates[std::size_t(n)] / 64, int(candidates[std::size_t(n)] % 64));
        float corner[8];
        for (int k = 0; k < 8; ++k) {
          const ivec3 q = glm::min(c + ivec3(k & 1, (k >> 1) & 1, (k >> 2) & 1), dims - 1);
          corner[k] = data[std::size_t(q.x) + std::size_t(dims.x) * (std::size_t(q.y) + std::size_t(dims.y) * q.z)];
        }
        for (int probe = 0; probe < 7; ++probe) {
          const float* f = kProbes[probe];
          float read = 0.0f;
          for (int k = 0; k < 8; ++k) {
            read += corner[k] * (k & 1 ? f[0] : 1.0f - f[0]) * (k & 2 ? f[1] : 1.0f - f[1]) *
                    (k & 4 ? f[2] : 1.0f - f[2]);
          }
          const float truth = exp_nonpositive(-probe_depth[std::size_t(n) * 7 + std::size_t(probe)]);
          if (std::abs(truth - read) > probe_tolerance) {
            keep[std::size_t(n)] = 1;
            break;
          }
        }
      }
    });
    std::fill(masks_.begin(), masks_.end(), std::uint64_t(0));
    for (std::size_t n = 0; n < candidates.size(); ++n) {
      if (keep[n]) masks_[std::size_t(candidates[n] / 64)] |= std::uint64_t(1) << (candidates[n] % 64);
    }
    std::vector<float>().swap(probe_depth);
    allocate(refine);
    // The bricks' cells, in brick order (block, then bit).
    std::vector<ivec3> brick_cells;
    brick_cells.reserve(brick_count_);
    for (std::int64_t block = 0; block < block_count; ++block) {
      for (std::uint64_t mask = masks_[std::size_t(block)]; mask != 0; mask &= mask - 1) {
        brick_cells.push_back(cell_of(block, __builtin_ctzll(mask)));
      }
    }
    const int n = refine;
    const std::int64_t per_brick = std::int64_t(n) * n * n;
    check_memory_budget("the shadow cache's refined cells: their texels' depths",
                        checked_product({std::uint64_t(brick_cells.size()), std::uint64_t(per_brick), sizeof(float)}));
    std::vector<float> tau(brick_cells.size() * std::size_t(per_brick));
    evaluate_batch(
        depth, std::int64_t(tau.size()),
        [&](std::int64_t t) {
          const std::int64_t texel = t % per_brick;
          const vec3 sub(float(texel % n), float(texel / n % n), float(texel / (n * n)));
          return view.world_from_index(vec3(brick_cells[std::size_t(t / per_brick)]) + (sub + 0.5f) / float(n));
        },
        tau.data());
    parallel_for(0, std::int64_t(tau.size()), [&](std::int64_t first, std::int64_t last) {
      for (std::int64_t t = first; t < last; ++t) {
        const float clamped = glm::clamp(tau[std::size_t(t)], 0.0f, RefinedCellsView::kMaxDepth);
        texels_[std::size_t(t)] = std::uint16_t(clamped * (65535.0f / RefinedCellsView::kMaxDepth) + 0.5f);
      }
    });
    view_.block_first = first_.data();
    view_.block_mask = masks_.data();
    view_.texels = texels_.data();
  }

  void clear();
  const RefinedCellsView& view() const { return view_; }
  std::size_t brick_count() const { return brick_count_; }
  std::uint64_t bytes() const;

 private:
  // The masks of the cells whose texels differ by more than `tolerance`.
  void plan(const Volume& cache, float tolerance, int refine);
  // The first brick of each block, and the bricks, for the masks.
  void allocate(int refine);

  RefinedCellsView view_;
  std::vector<std::uint32_t> first_;
  std::vector<std::uint64_t> masks_;
  std::vector<std::uint16_t> texels_;
  std::size_t brick_count_ = 0;
};

}  // namespace penumbra

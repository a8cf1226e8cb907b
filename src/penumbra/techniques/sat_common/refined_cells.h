#pragma once
// Refined cells of a shadow cache (issue 22): for each cache cell whose eight
// texels differ by more than a tolerance (where the visibility jumps, at lit
// surfaces and sharp shadow edges) and whose trilinear read misses the
// visibility at a probe, a brick of n^3 texels at the centres of the cell's
// n^3 sub-cells, so that rendering there reads a fine sample instead of the
// light tables. The tables can then be released once the cache and its
// bricks are filled.
//
// A brick's resolution follows its cell: n is the coarsest of 2, 4, ... up
// to the finest `refine` whose read meets the tolerance halfway between its
// texels, so a cell with a plane surface costs 8 texels and only the cells
// of thin or curved structures (a skull's bone under grazing light) take
// refine^3. Misses are measured on the cube root of the visibility, the
// scale of lightness (docs/filtered-sat.md, "Adaptive bricks").
//
// A brick's read is trilinear between its own texels only, extrapolated
// linearly over the half sub-cell between its outer texels and the cell's
// faces (so n >= 2). Texel-centred bricks hold n^3 texels where bricks on
// the cell's corners need (n + 1)^3 (2.4x more at n = 3): on the engine CT,
// centred n = 3 reads closer to the tables than corner bricks of 3
// (docs/filtered-sat.md, "Memory").
//
// Texels hold the optical depth tau (visibility = exp(-tau)) as 8-bit codes
// of the cube root of the visibility (brick_code below). Interpolating the
// depth rather than the visibility follows what lit surfaces hold: inside a
// material the depth grows about linearly with the distance from its
// surface while the visibility falls exponentially.
//
// Storage is sparse, per resolution: the cells are grouped in blocks of
// 4^3; each block keeps a 64-bit mask of the cells that have a brick of
// that resolution and the index of its first one, so a cell's brick is
// block_first + popcount(mask below its bit).
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

// Brick texels are 8-bit codes of the cube root of the visibility,
// code = round(255 exp(-tau / 3)), decoded to the optical depth
// tau = 3 ln(255 / code) through a table of the 256 depths (8 logs per read
// made filtered-sat's frames 1.4x slower): steps of 1/255 on the scale of
// lightness (a code's rounding costs at most 116 / 510 cbrt(Y) = 0.23 cbrt(Y)
// L*, Y the lit luminance), so that deep shadows need no more bits than the
// light. Code 0 reads kBrickMaxDepth (3 ln 510, where codes round to 0:
// visibility 7.5e-9).
inline constexpr float kBrickMaxDepth = 18.7071741f;

// The depth of each code (host memory; RefinedCellsView carries it, and a
// device mirror copies it).
const float* brick_depth_table();
inline std::uint8_t brick_code(float depth) {
  return std::uint8_t(255.0f * exp_nonpositive(-glm::max(depth, 0.0f) * (1.0f / 3.0f)) + 0.5f);
}

// The optical depth read in a brick of n^3 texels (x fastest) at `f`, the
// point's coordinates in its cell ([0, 1]^3): trilinear between the texels'
// depths (sub-cell centres, `depth_of_code` from brick_depth_table),
// extrapolated linearly over the half sub-cells between the outer texels
// and the cell's faces.
PENUMBRA_HD inline float brick_depth(const std::uint8_t* t, int n, vec3 f, const float* depth_of_code) {
  const vec3 s = f * float(n) - 0.5f;
  const ivec3 base = glm::clamp(ivec3(glm::floor(s)), ivec3(0), ivec3(n - 2));
  const int sy = n, sz = n * n;
  auto lerp = [](float a, float b, float w) { return a + w * (b - a); };
  const vec3 w = s - vec3(base);
  const std::uint8_t* p = t + base.x + sy * base.y + sz * base.z;
  const float* d = depth_of_code;
  const float x00 = lerp(d[p[0]], d[p[1]], w.x), x10 = lerp(d[p[sy]], d[p[sy + 1]], w.x);
  const float x01 = lerp(d[p[sz]], d[p[sz + 1]], w.x), x11 = lerp(d[p[sz + sy]], d[p[sz + sy + 1]], w.x);
  return lerp(lerp(x00, x10, w.y), lerp(x01, x11, w.y), w.z);
}

// One resolution of bricks: the cells of 4^3-cell blocks that have a brick
// of refine^3 texels at this level.
struct BrickLevelView {
  int refine = 0;  // texels per cell edge (>= 2)
  std::uint32_t bricks = 0;
  const std::uint32_t* block_first = nullptr;  // per block
  const std::uint64_t* block_mask = nullptr;   // per block
  const std::uint8_t* texels = nullptr;        // bricks of refine^3 texel codes (brick_code), x fastest
};

struct RefinedCellsView {
  static constexpr int kMaxLevels = 4;  // refine 2, 4, 6, 8 at the most
  ivec3 cells{0};   // cache cells per axis (cache dims - 1)
  ivec3 blocks{0};  // blocks of 4^3 cells per axis
  int levels = 0;   // 0: no bricks
  BrickLevelView level[kMaxLevels];  // coarsest first; a cell has a brick in one level at most
  const float* depth_of_code = nullptr;  // brick_depth_table(), where levels > 0

  // The brick's visibility at `world` into `value`: exp of the depth
  // interpolated in the brick; false where the cell holding `world`
  // (clamped to the cache, as its trilinear read) has no brick.
  PENUMBRA_HD bool sample(const VolumeView& cache, vec3 world, float& value) const {
    if (levels <= 0) return false;
    const vec3 g = glm::clamp((world - cache.origin) / cache.spacing, vec3(0.0f), vec3(cells));
    const ivec3 c = glm::min(ivec3(g), cells - 1);
    const ivec3 b = c >> 2;
    const int block = b.x + blocks.x * (b.y + blocks.y * b.z);
    const int bit = (c.x & 3) + 4 * (c.y & 3) + 16 * (c.z & 3);
    for (int l = 0; l < levels; ++l) {
      const BrickLevelView& v = level[l];
      if (v.bricks == 0) continue;
      const std::uint64_t mask = v.block_mask[block];
      if (((mask >> bit) & 1u) == 0) continue;
      const std::uint64_t below = mask & ((std::uint64_t(1) << bit) - 1u);
      const int n = v.refine;
      const std::uint8_t* t =
          v.texels + (std::size_t(v.block_first[block]) + std::size_t(popcount64(below))) * std::size_t(n * n * n);
      value = exp_nonpositive(-glm::max(brick_depth(t, n, g - vec3(c), depth_of_code), 0.0f));
      return true;
    }
    return false;
  }
};

class RefinedCells {
 public:
  // Bricks (refine >= 2) for the cells of `cache` (a float visibility grid
  // from build_visibility_cache) whose texels differ by more than
  // `tolerance` and where the cache's trilinear read misses the visibility
  // exp(-depth(world)) at one of seven probes (the cell's centre and its
  // faces' centres; a smooth ramp across a penumbra needs no brick), filled
  // with depth(world), the optical depth toward the light. Misses are
  // measured on the cube root of the visibility against `probe_tolerance`.
  // A brick's resolution follows its cell: the levels are 2, 4, ... up to
  // refine (and refine itself where it is odd), and a cell keeps the
  // coarsest brick that does not miss at its checks (the points halfway
  // between its texels, and the faces' centres); the finest level takes the
  // rest. Throws OutOfMemoryBudget before allocating what does not fit.
  // `depth` may also be a batch (sat_common/batch.h): the probes and the
  // 2^3 bricks are evaluated as one batch, then each finer level's texels
  // and checks as another.
  template <class Depth>
  void build(const Volume& cache, float tolerance, float probe_tolerance, int refine, const Depth& depth) {
    plan(cache, tolerance, refine);
    const VolumeView view = cache.view();
    const float* data = cache.frame_as<float>(0);
    const VoxelGrid grid(cache.dims());
    // The candidates, in block and bit order.
    std::vector<std::int64_t> cells;  // block * 64 + bit
    for (std::size_t block = 0; block < masks_[0].size(); ++block) {
      for (std::uint64_t mask = masks_[0][block]; mask != 0; mask &= mask - 1) {
        cells.push_back(std::int64_t(block) * 64 + __builtin_ctzll(mask));
      }
    }
    // Level by level, coarsest first: the texels and checks of the cells
    // still without a brick as one batch; the cells whose brick reads the
    // checks well keep it, the others go on to the next level. The first
    // level (2^3) is built for every candidate: its checks are the probes
    // (the centre and the faces' centres), where a candidate whose cache
    // cell reads them well needs no brick at all.
    std::vector<std::uint8_t> keep;
    for (int l = 0; l < view_.levels; ++l) {
      const int n = view_.level[l].refine;
      const bool finest = l + 1 == view_.levels;
      const std::vector<vec3> checks = finest && l > 0 ? std::vector<vec3>() : check_points(l == 0 ? 2 : n);
      const std::int64_t per_brick = std::int64_t(n) * n * n;
      const std::int64_t per_cell = per_brick + std::int64_t(checks.size());
      check_memory_budget("the shadow cache's refined cells: their texels' depths",
                          checked_product({std::uint64_t(cells.size()), std::uint64_t(per_cell), sizeof(float) + 3}));
      std::vector<float> tau(cells.size() * std::size_t(per_cell));
      evaluate_batch(
          depth, std::int64_t(tau.size()),
          [&](std::int64_t t) {
            const std::int64_t i = t % per_cell;
            const vec3 f = i < per_brick
                               ? (vec3(float(i % n), float(i / n % n), float(i / (n * n))) + 0.5f) / float(n)
                               : checks[std::size_t(i - per_brick)];
            return view.world_from_index(vec3(cell_of(cells[std::size_t(t / per_cell)])) + f);
          },
          tau.data());
      std::vector<std::uint8_t> texels(cells.size() * std::size_t(per_brick));
      keep.assign(cells.size(), 0);
      std::vector<std::uint8_t> needed(cells.size(), 1);
      parallel_for(0, std::int64_t(cells.size()), [&](std::int64_t first, std::int64_t last) {
        for (std::int64_t c = first; c < last; ++c) {
          const float* in = tau.data() + c * per_cell;
          auto truth = [&](std::size_t k) {
            return exp_nonpositive(-glm::max(in[per_brick + std::int64_t(k)], 0.0f));
          };
          if (l == 0) {  // does the cache cell miss a probe?
            bool missed = false;
            for (std::size_t k = 0; k < checks.size() && !missed; ++k) {
              const vec3 at = vec3(cell_of(cells[std::size_t(c)])) + checks[k];
              missed = perceptual_miss(trilinear<ScalarLanes>(grid, data, at), truth(k), probe_tolerance);
            }
            needed[std::size_t(c)] = missed ? 1 : 0;
            if (!missed) continue;
          }
          std::uint8_t* out = texels.data() + c * per_brick;
          for (std::int64_t i = 0; i < per_brick; ++i) out[i] = brick_code(in[i]);
          bool good = true;
          for (std::size_t k = 0; k < checks.size() && good && !finest; ++k) {
            const float read = exp_nonpositive(-glm::max(brick_depth(out, n, checks[k], view_.depth_of_code), 0.0f));
            good = !perceptual_miss(read, truth(k), probe_tolerance);
          }
          keep[std::size_t(c)] = good ? 1 : 0;
        }
      });
      std::vector<float>().swap(tau);
      store(l, cells, keep, texels);
      // On: the cells that need a brick and did not keep this one.
      std::vector<std::int64_t> next;
      for (std::size_t c = 0; c < cells.size(); ++c) {
        if (needed[c] && !keep[c]) next.push_back(cells[c]);
      }
      cells.swap(next);
    }
  }

  // view_ points into the vectors below: a move keeps their buffers, a copy
  // would leave the copy's view on the original's (filtered-sat keeps one
  // per light in a vector, which copied them when a light was added and read
  // freed bricks: SceneEdits.GiveTheImageOfAFreshTechnique). The
  // move is noexcept (vector growth moves, never copies) though glm's vectors
  // in the view do not say so.
  RefinedCells() = default;
  RefinedCells(RefinedCells&&) noexcept = default;
  RefinedCells& operator=(RefinedCells&&) noexcept = default;
  RefinedCells(const RefinedCells&) = delete;
  RefinedCells& operator=(const RefinedCells&) = delete;

  void clear();
  const RefinedCellsView& view() const { return view_; }
  std::size_t brick_count() const;
  std::size_t brick_count(int level) const { return level < view_.levels ? view_.level[level].bricks : 0; }
  std::uint64_t bytes() const;

 private:
  // Whether `read` misses the visibility `truth` by more than `tolerance`
  // on the cube root of the visibility (lightness L* = 116 Y^(1/3) - 16, so
  // that a miss costs about as much lightness in a shadow as in the light).
  static bool perceptual_miss(float read, float truth, float tolerance) {
    return std::abs(std::cbrt(glm::max(read, 0.0f)) - std::cbrt(glm::max(truth, 0.0f))) > tolerance;
  }
  ivec3 cell_of(std::int64_t cell) const {
    const std::int64_t block = cell / 64;
    const int bit = int(cell % 64);
    const ivec3 blocks = view_.blocks;
    const ivec3 b(int(block % blocks.x), int(block / blocks.x % blocks.y), int(block / blocks.x / blocks.y));
    return b * 4 + ivec3(bit & 3, (bit >> 2) & 3, bit >> 4);
  }
  // Where a brick of n^3 texels is checked before a finer one replaces it:
  // halfway between its texels (the lattice k / n, 0 < k < n) and the
  // centres of the cell's faces (where it extrapolates).
  static std::vector<vec3> check_points(int n);
  // The masks of the cells whose texels differ by more than `tolerance`
  // (in masks_[0], the candidates), and the levels of `refine`.
  void plan(const Volume& cache, float tolerance, int refine);
  // Level l's bricks: those of `cells` whose keep flag is set, with their
  // texels (per_brick each, in the order of `cells`).
  void store(int l, const std::vector<std::int64_t>& cells, const std::vector<std::uint8_t>& keep,
             const std::vector<std::uint8_t>& texels);

  RefinedCellsView view_;
  std::vector<std::uint32_t> first_[RefinedCellsView::kMaxLevels];
  std::vector<std::uint64_t> masks_[RefinedCellsView::kMaxLevels];
  std::vector<std::uint8_t> texels_[RefinedCellsView::kMaxLevels];
};

}  // namespace penumbra

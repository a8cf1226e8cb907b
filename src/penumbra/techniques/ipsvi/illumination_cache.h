#pragma once
// IPSVI's illumination cache (Sundén et al. 2011, sections 4.3 and 4.4): a 2D
// light-space image holding, per texel, the light that has reached the
// current sweep plane along that texel's light ray, and the depth along the
// ray where that value holds (the paper keeps the position of the sample that
// wrote it, for the piecewise integration).
//
// Ping-pong (4.2): while the rays of a block of lines run in parallel they read
// only the state left by earlier blocks and add their writes to a separate
// set of sums; resolve() then folds the sums into the state. A texel that
// several rays write gets the weighted mean of their values (the GPU version
// keeps whichever write lands last). The sums are fixed-point integers so the
// result does not depend on the order in which threads add them.
#include "penumbra/base/math.h"
#include "penumbra/base/parallel.h"
#include "penumbra/techniques/ipsvi/light_cache_projection.h"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace penumbra {

// What a sample reads from the cache: transmittance of the direct light, of
// the diffuse (forward-scattered) light, and the depth where they hold; with
// the paper's light model (light_model.h) also the direct light's colour,
// Eq. 3's I_ss relative to the light's (`direct` is then unused).
struct CachedLight {
  float direct = 1.0f;
  float depth = 0.0f;
  vec3 diffuse{1.0f};
  vec3 color{1.0f};
};

struct IlluminationCacheView {
  // Sums per texel: weight, direct, depth, then the diffuse rgb with the
  // diffuse channel and the direct light's rgb with colour (the paper's light
  // model), in that order.
  PENUMBRA_HD static constexpr int sums_per_texel(bool with_diffuse, bool with_color) {
    return 3 + (with_diffuse ? 3 : 0) + (with_color ? 3 : 0);
  }
  static constexpr float kValueScale = 16777216.0f;  // 2^24: fixed-point unit of a value in [0, 1]
  static constexpr float kWeightScale = 65536.0f;    // 2^16

  int size = 0;  // texels along u (a row)
  int rows = 0;  // texels along v
  const vec2* state = nullptr;    // per texel: (direct transmittance, depth)
  const vec4* diffuse = nullptr;  // per texel: diffuse transmittance (rgb); null without the diffuse part
  const vec4* color = nullptr;    // per texel: the direct light's rgb; null but with the paper's light model
  std::uint64_t* sums = nullptr;  // sums_per_texel per texel: the writes of the current block
  std::uint32_t* touched = nullptr;
  std::uint32_t* touched_count = nullptr;
  float max_depth = 1.0f;

  PENUMBRA_HD bool covers(vec2 uv) const {
    return uv.x >= 0.0f && uv.y >= 0.0f && uv.x <= float(size) && uv.y <= float(rows);
  }

  // The texel containing uv (which must be covered).
  PENUMBRA_HD int texel_index(vec2 uv) const {
    const int x = glm::clamp(int(uv.x), 0, size - 1);
    const int y = glm::clamp(int(uv.y), 0, rows - 1);
    return x + size * y;
  }

  // Bilinear read of the direct light and depth (diffuse: the unfiltered
  // value at uv). Outside the cache nothing shadows: transmittance 1 at an
  // infinite depth, so no light segment is marched.
  PENUMBRA_HD CachedLight read(vec2 uv, bool with_diffuse) const {
    CachedLight out;
    if (!covers(uv)) {
      out.depth = kInfinity;
      return out;
    }
    int x0, y0, x1, y1;
    float fx, fy;
    corners(uv, x0, y0, x1, y1, fx, fy);
    const vec2 a = state[x0 + size * y0], b = state[x1 + size * y0];
    const vec2 c = state[x0 + size * y1], d = state[x1 + size * y1];
    const vec2 v = glm::mix(glm::mix(a, b, fx), glm::mix(c, d, fx), fy);
    out.direct = v.x;
    out.depth = v.y;
    if (with_diffuse) out.diffuse = diffuse_at(uv);
    return out;
  }

  // The four texels of a bilinear read at uv (covered) and their weights.
  PENUMBRA_HD void taps(vec2 uv, int texel[4], float weight[4]) const {
    int x0, y0, x1, y1;
    float fx, fy;
    corners(uv, x0, y0, x1, y1, fx, fy);
    texel[0] = x0 + size * y0;
    texel[1] = x1 + size * y0;
    texel[2] = x0 + size * y1;
    texel[3] = x1 + size * y1;
    weight[0] = (1.0f - fx) * (1.0f - fy);
    weight[1] = fx * (1.0f - fy);
    weight[2] = (1.0f - fx) * fy;
    weight[3] = fx * fy;
  }

  // Diffuse light filtered with a Gaussian of standard deviation `sigma`
  // texels along each axis: five bilinear taps (centre and +-r along both
  // axes) whose weights give the variance sigma^2 per axis.
  PENUMBRA_HD vec3 read_diffuse(vec2 uv, vec2 sigma) const {
    if (!covers(uv)) return vec3(1.0f);
    if (!(glm::max(sigma.x, sigma.y) > 0.05f)) return diffuse_at(uv);
    const vec2 r = glm::max(vec2(1.0f), sigma * 1.5811388f);  // keeps the centre weight >= 0.2
    const vec2 w = glm::min(sigma * sigma / (2.0f * r * r), vec2(0.2f));
    vec3 sum = (1.0f - 2.0f * w.x - 2.0f * w.y) * diffuse_at(uv);
    sum += w.x * (diffuse_at(uv + vec2(r.x, 0.0f)) + diffuse_at(uv - vec2(r.x, 0.0f)));
    sum += w.y * (diffuse_at(uv + vec2(0.0f, r.y)) + diffuse_at(uv - vec2(0.0f, r.y)));
    return sum;
  }

  // Adds one write (the weighted mean of a run of samples in one texel, with
  // its total weight) to the block's sums. Writes that would move the texel's
  // value back toward the light are dropped: the cache only advances.
  PENUMBRA_HD void write(int texel, float weight, float direct, float depth, vec3 diffuse_light,
                         vec3 color_light = vec3(1.0f)) const {
    if (!(weight > 0.0f) || !(depth > state[texel].y)) return;
    const std::uint64_t w = std::uint64_t(weight * kWeightScale) + 1u;
    std::uint64_t* s = sums + std::int64_t(texel) * sums_per_texel(diffuse != nullptr, color != nullptr);
    if (fetch_add(s[0], w) == 0u) touched[fetch_add32(*touched_count, 1u)] = std::uint32_t(texel);
    fetch_add(s[1], w * quantize(direct));
    fetch_add(s[2], w * quantize(depth / max_depth));
    if (diffuse) {
      fetch_add(s[3], w * quantize(diffuse_light.r));
      fetch_add(s[4], w * quantize(diffuse_light.g));
      fetch_add(s[5], w * quantize(diffuse_light.b));
    }
    if (color) {
      std::uint64_t* c = s + (diffuse ? 6 : 3);
      fetch_add(c[0], w * quantize(color_light.r));
      fetch_add(c[1], w * quantize(color_light.g));
      fetch_add(c[2], w * quantize(color_light.b));
    }
  }

  // The direct light's colour at uv (bilinear; covered), paper's model only.
  PENUMBRA_HD vec3 color_at(vec2 uv) const {
    int x0, y0, x1, y1;
    float fx, fy;
    corners(uv, x0, y0, x1, y1, fx, fy);
    const vec3 a(color[x0 + size * y0]), b(color[x1 + size * y0]);
    const vec3 c(color[x0 + size * y1]), d(color[x1 + size * y1]);
    return glm::mix(glm::mix(a, b, fx), glm::mix(c, d, fx), fy);
  }

 private:
  PENUMBRA_HD void corners(vec2 uv, int& x0, int& y0, int& x1, int& y1, float& fx, float& fy) const {
    const float x = glm::clamp(uv.x - 0.5f, 0.0f, float(size - 1));
    const float y = glm::clamp(uv.y - 0.5f, 0.0f, float(rows - 1));
    x0 = int(x);
    y0 = int(y);
    x1 = glm::min(x0 + 1, size - 1);
    y1 = glm::min(y0 + 1, rows - 1);
    fx = x - float(x0);
    fy = y - float(y0);
  }

  PENUMBRA_HD vec3 diffuse_at(vec2 uv) const {
    int x0, y0, x1, y1;
    float fx, fy;
    corners(uv, x0, y0, x1, y1, fx, fy);
    const vec3 a(diffuse[x0 + size * y0]), b(diffuse[x1 + size * y0]);
    const vec3 c(diffuse[x0 + size * y1]), d(diffuse[x1 + size * y1]);
    return glm::mix(glm::mix(a, b, fx), glm::mix(c, d, fx), fy);
  }

  PENUMBRA_HD static std::uint64_t quantize(float value) {
    return std::uint64_t(glm::clamp(value, 0.0f, 1.0f) * kValueScale + 0.5f);
  }
  PENUMBRA_HD static std::uint64_t fetch_add(std::uint64_t& target, std::uint64_t value) {
    return __atomic_fetch_add(&target, value, __ATOMIC_RELAXED);
  }
  PENUMBRA_HD static std::uint32_t fetch_add32(std::uint32_t& target, std::uint32_t value) {
    return __atomic_fetch_add(&target, value, __ATOMIC_RELAXED);
  }
};

// The cache at the start of a sweep for one light: every texel unlit-by-
// nothing (transmittance 1) at the depth where its light ray enters the
// volume box and clip planes, so that piecewise integration from a texel
// nobody has written yet marches the whole way to the light's side of the box.
std::vector<vec2> initial_cache_state(const LightCacheProjection& projection, const Box3& box,
                                      const std::vector<vec4>& clip_planes);

class IlluminationCache {
 public:
  // Room for `texels` texels (the largest of the lights' grids). Checks the
  // memory budget; `diffuse` adds the forward-scattering channel, `colored`
  // the direct light's colour (the paper's light model).
  void allocate(std::uint64_t texels, bool diffuse, bool colored = false);
  // Starts a sweep of a `size` x `rows` grid (a light's projection, within
  // the allocation) from `initial` (see initial_cache_state).
  void reset(const std::vector<vec2>& initial, int size, int rows);
  IlluminationCacheView view(float max_depth);
  // Folds the writes of the last block into the state and clears them. For
  // each written texel advance(texel, stored, written) gives its new light,
  // with `stored` what the texel held and `written` the weighted mean of the
  // block's writes (at a greater depth). All texels are advanced before any
  // is changed, so advance may read any texel of the state.
  template <class Advance> void resolve(const Advance& advance);
  // The same, a chunk of texels at a time: advance(n, texels, stored,
  // written, out) gives out[i] for texels[i] (n <= kResolveChunk), for the
  // texels whose writes lie beyond what they held.
  static constexpr int kResolveChunk = 64;
  template <class AdvanceChunk> void resolve_chunks(const AdvanceChunk& advance);

  std::uint64_t capacity() const { return state_.size(); }
  std::uint64_t bytes() const;

 private:
  int size_ = 0, rows_ = 0;
  float max_depth_ = 1.0f;
  std::vector<vec2> state_;
  std::vector<vec4> diffuse_;
  std::vector<vec4> color_;
  std::vector<std::uint64_t> sums_;
  std::vector<std::uint32_t> touched_;
  std::uint32_t touched_count_ = 0;
  std::vector<vec2> staged_;          // resolve(): the new light (direct, depth) of each touched texel
  std::vector<vec3> staged_diffuse_;  // its diffuse light (with the diffuse channel)
  std::vector<vec3> staged_color_;    // and its colour (paper's light model)
};

template <class Advance> void IlluminationCache::resolve(const Advance& advance) {
  resolve_chunks([&](int n, const int* texels, const CachedLight* stored, const CachedLight* written,
                     CachedLight* out) {
    for (int i = 0; i < n; ++i) out[i] = advance(texels[i], stored[i], written[i]);
  });
}

template <class AdvanceChunk> void IlluminationCache::resolve_chunks(const AdvanceChunk& advance) {
  const std::int64_t count = touched_count_;
  const bool diffuse = !diffuse_.empty();
  const bool colored = !color_.empty();
  const int stride = IlluminationCacheView::sums_per_texel(diffuse, colored);
  const int color_sums = diffuse ? 6 : 3;
  parallel_for(
      0, count,
      [&](std::int64_t first, std::int64_t last) {
        int texels[kResolveChunk], slots[kResolveChunk];
        CachedLight stored[kResolveChunk], written[kResolveChunk], out[kResolveChunk];
        for (std::int64_t begin = first; begin < last; begin += kResolveChunk) {
          const std::int64_t end = std::min(last, begin + kResolveChunk);
          int n = 0;
          for (std::int64_t i = begin; i < end; ++i) {
            const std::uint32_t texel = touched_[std::size_t(i)];
            std::uint64_t* s = sums_.data() + std::size_t(texel) * std::size_t(stride);
            const double w = double(s[0]) * IlluminationCacheView::kValueScale;
            const CachedLight held{state_[texel].x, state_[texel].y, diffuse ? vec3(diffuse_[texel]) : vec3(1.0f),
                                   colored ? vec3(color_[texel]) : vec3(1.0f)};
            CachedLight mean{float(double(s[1]) / w), float(double(s[2]) / w) * max_depth_, vec3(1.0f), vec3(1.0f)};
            if (diffuse) mean.diffuse = vec3(float(double(s[3]) / w), float(double(s[4]) / w), float(double(s[5]) / w));
            if (colored) {
              const std::uint64_t* c = s + color_sums;
              mean.color = vec3(float(double(c[0]) / w), float(double(c[1]) / w), float(double(c[2]) / w));
            }
            std::fill(s, s + stride, 0u);
            if (mean.depth > held.depth) {
              texels[n] = int(texel);
              slots[n] = int(i - begin);
              stored[n] = held;
              written[n] = mean;
              ++n;
            }
            out[i - begin] = held;  // kept unless advanced below
          }
          // The advanced texels' new light, back to their places in the chunk.
          CachedLight advanced[kResolveChunk];
          if (n > 0) advance(n, texels, stored, written, advanced);
          for (int j = 0; j < n; ++j) out[slots[j]] = advanced[j];
          for (std::int64_t i = begin; i < end; ++i) {
            const CachedLight& c = out[i - begin];
            staged_[std::size_t(i)] = vec2(c.direct, c.depth);
            if (diffuse) staged_diffuse_[std::size_t(i)] = c.diffuse;
            if (colored) staged_color_[std::size_t(i)] = c.color;
          }
        }
      },
      kResolveChunk);
  parallel_for(
      0, count,
      [&](std::int64_t first, std::int64_t last) {
        for (std::int64_t i = first; i < last; ++i) {
          const std::uint32_t texel = touched_[std::size_t(i)];
          state_[texel] = staged_[std::size_t(i)];
          if (diffuse) diffuse_[texel] = vec4(staged_diffuse_[std::size_t(i)], 1.0f);
          if (colored) color_[texel] = vec4(staged_color_[std::size_t(i)], 1.0f);
        }
      },
      256);
  touched_count_ = 0;
}

}  // namespace penumbra

#include "penumbra/techniques/ipsvi/illumination_cache.h"

#include "penumbra/base/error.h"
#include "penumbra/base/memory_budget.h"
#include "penumbra/base/parallel.h"


namespace penumbra {

std::vector<vec2> initial_cache_state(const LightCacheProjection& projection, const Box3& box,
                                      const std::vector<vec4>& clip_planes) {
  const int n = projection.size, rows = projection.rows;
  // Where each texel's light ray enters the box and clip planes (-1: it
  // misses them).
  std::vector<float> entry(std::size_t(n) * rows);
  parallel_for(0, rows, [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t y = first; y < last; ++y) {
      for (int x = 0; x < n; ++x) {
        const Ray ray = projection.texel_ray(vec2(float(x) + 0.5f, float(y) + 0.5f));
        const Interval iv = clip_interval(ray, clip_planes.data(), int(clip_planes.size()),
                                          intersect_box(ray, box, 0.0f, kInfinity));
        entry[std::size_t(x + n * y)] = iv.empty() ? -1.0f : iv.t0;
      }
    }
  });
  // A texel starts at the earliest entry of its 3x3 neighbourhood: a sample
  // reads the four texels around it, and on a face the light grazes (a cut
  // face) the entries of neighbouring texels differ by many steps, so a
  // texel starting at its own entry would be ahead of a sample just inside
  // the face beside it and be left out of its read, in a pattern of the
  // cache grid. Starting earlier costs only empty space: a segment marched
  // toward the light is clipped to the box and planes. Light rays whose
  // whole neighbourhood misses the volume keep depth 0.
  std::vector<vec2> state(std::size_t(n) * rows);
  parallel_for(0, rows, [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t y = first; y < last; ++y) {
      for (int x = 0; x < n; ++x) {
        float earliest = kInfinity;
        for (int dy = -1; dy <= 1; ++dy) {
          for (int dx = -1; dx <= 1; ++dx) {
            const int xx = x + dx, yy = int(y) + dy;
            if (xx < 0 || yy < 0 || xx >= n || yy >= rows) continue;
            const float e = entry[std::size_t(xx + n * yy)];
            if (e >= 0.0f) earliest = glm::min(earliest, e);
          }
        }
        state[std::size_t(x + n * y)] = vec2(1.0f, earliest < kInfinity ? earliest : 0.0f);
      }
    }
  });
  return state;
}

void IlluminationCache::allocate(std::uint64_t texels, bool diffuse, bool colored) {
  const int stride = IlluminationCacheView::sums_per_texel(diffuse, colored);
  const std::uint64_t per_texel = sizeof(vec2) + (diffuse ? sizeof(vec4) : 0) +
                                  (colored ? sizeof(vec4) + sizeof(vec3) : 0) +
                                  std::uint64_t(stride) * sizeof(std::uint64_t) + sizeof(std::uint32_t) +
                                  sizeof(vec2) + (diffuse ? sizeof(vec3) : 0);
  check_memory_budget("ipsvi illumination cache", checked_product({texels, per_texel}));
  size_ = rows_ = 0;
  state_.assign(texels, vec2(1.0f, 0.0f));
  if (diffuse) {
    diffuse_.assign(texels, vec4(1.0f));
  } else {
    diffuse_.clear();
    diffuse_.shrink_to_fit();
  }
  if (colored) {
    color_.assign(texels, vec4(1.0f));
  } else {
    color_.clear();
    color_.shrink_to_fit();
  }
  sums_.assign(texels * std::uint64_t(stride), 0u);
  touched_.assign(texels, 0u);
  touched_count_ = 0;
  staged_.resize(texels);
  staged_diffuse_.resize(diffuse ? texels : 0);
  staged_diffuse_.shrink_to_fit();
  staged_color_.resize(colored ? texels : 0);
  staged_color_.shrink_to_fit();
}

void IlluminationCache::reset(const std::vector<vec2>& initial, int size, int rows) {
  if (initial.size() != std::size_t(size) * std::size_t(rows) || initial.size() > state_.size()) {
    throw Error("ipsvi: a light's cache grid does not fit the allocated cache");
  }
  size_ = size;
  rows_ = rows;
  std::copy(initial.begin(), initial.end(), state_.begin());
  std::fill(diffuse_.begin(), diffuse_.end(), vec4(1.0f));
  std::fill(color_.begin(), color_.end(), vec4(1.0f));
}

IlluminationCacheView IlluminationCache::view(float max_depth) {
  max_depth_ = glm::max(max_depth, 1e-6f);
  IlluminationCacheView v;
  v.size = size_;
  v.rows = rows_;
  v.state = state_.data();
  v.diffuse = diffuse_.empty() ? nullptr : diffuse_.data();
  v.color = color_.empty() ? nullptr : color_.data();
  v.sums = sums_.data();
  v.touched = touched_.data();
  v.touched_count = &touched_count_;
  v.max_depth = max_depth_;
  return v;
}

std::uint64_t IlluminationCache::bytes() const {
  return state_.size() * sizeof(vec2) + (diffuse_.size() + color_.size()) * sizeof(vec4) +
         sums_.size() * sizeof(std::uint64_t) +
         touched_.size() * sizeof(std::uint32_t) + staged_.size() * sizeof(vec2) + staged_diffuse_.size() * sizeof(vec3) +
         staged_color_.size() * sizeof(vec3);
}

}  // namespace penumbra

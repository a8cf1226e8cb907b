#include "penumbra/techniques/ipsvi/illumination_cache.h"

#include "penumbra/base/memory_budget.h"
#include "penumbra/base/parallel.h"


namespace penumbra {

std::vector<vec2> initial_cache_state(const LightCacheProjection& projection, const Box3& box,
                                      const std::vector<vec4>& clip_planes) {
  const int n = projection.size;
  std::vector<vec2> state(std::size_t(n) * n);
  parallel_for(0, n, [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t y = first; y < last; ++y) {
      for (int x = 0; x < n; ++x) {
        const Ray ray = projection.texel_ray(vec2(float(x) + 0.5f, float(y) + 0.5f));
        const Interval entry = clip_interval(ray, clip_planes.data(), int(clip_planes.size()),
                                             intersect_box(ray, box, 0.0f, kInfinity));
        // Light rays that miss the volume keep depth 0: a segment marched
        // toward it is clipped to the box anyway.
        state[std::size_t(x + n * y)] = vec2(1.0f, entry.empty() ? 0.0f : entry.t0);
      }
    }
  });
  return state;
}

void IlluminationCache::allocate(int size, bool diffuse) {
  const std::uint64_t texels = std::uint64_t(size) * std::uint64_t(size);
  const std::uint64_t per_texel = sizeof(vec2) + (diffuse ? sizeof(vec4) : 0) +
                                  IlluminationCacheView::kSums * sizeof(std::uint64_t) + sizeof(std::uint32_t) +
                                  sizeof(CachedLight);
  check_memory_budget("ipsvi illumination cache", checked_product({texels, per_texel}));
  size_ = size;
  state_.assign(texels, vec2(1.0f, 0.0f));
  if (diffuse) {
    diffuse_.assign(texels, vec4(1.0f));
  } else {
    diffuse_.clear();
    diffuse_.shrink_to_fit();
  }
  sums_.assign(texels * IlluminationCacheView::kSums, 0u);
  touched_.assign(texels, 0u);
  touched_count_ = 0;
  staged_.resize(texels);
}

void IlluminationCache::reset(const std::vector<vec2>& initial) {
  std::copy(initial.begin(), initial.end(), state_.begin());
  std::fill(diffuse_.begin(), diffuse_.end(), vec4(1.0f));
}

IlluminationCacheView IlluminationCache::view(float max_depth) {
  max_depth_ = glm::max(max_depth, 1e-6f);
  IlluminationCacheView v;
  v.size = size_;
  v.state = state_.data();
  v.diffuse = diffuse_.empty() ? nullptr : diffuse_.data();
  v.sums = sums_.data();
  v.touched = touched_.data();
  v.touched_count = &touched_count_;
  v.max_depth = max_depth_;
  return v;
}

std::uint64_t IlluminationCache::bytes() const {
  return state_.size() * sizeof(vec2) + diffuse_.size() * sizeof(vec4) + sums_.size() * sizeof(std::uint64_t) +
         touched_.size() * sizeof(std::uint32_t) + staged_.size() * sizeof(CachedLight);
}

}  // namespace penumbra

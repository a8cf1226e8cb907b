#pragma once
// The shadow cache of Ament et al. 2014, Algorithm 1: a float grid over the
// volume's world box holding one light's visibility per texel, so that
// rendering reads one trilinear sample instead of evaluating the tables per
// viewing-ray sample. Texel (0, 0, 0) sits on the box's lower corner and the
// last texel on its upper corner (the layout of shadow-rays' cache).
#include "penumbra/base/parallel.h"
#include "penumbra/render/parameters.h"
#include "penumbra/volume/volume.h"

#include <cstdint>
#include <vector>

namespace penumbra {

// Texels per axis for a volume of `data_dims` at `resolution` texels per
// voxel (at least 2 per axis).
ivec3 visibility_cache_dims(ivec3 data_dims, float resolution);

// A cache of `dims` texels over `box` with texel value visibility(world).
template <class Visibility> Volume build_visibility_cache(const Box3& box, ivec3 dims, const Visibility& visibility) {
  Volume cache(dims, VoxelType::Float32);
  cache.set_spacing(glm::max(box.extent() / vec3(dims - 1), vec3(1e-6f)));
  cache.set_origin(box.lower);
  float* texels = cache.frame_as<float>(0);
  const VolumeView view = cache.view();
  parallel_for(0, std::int64_t(dims.z) * dims.y, [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t row = first; row < last; ++row) {
      const int y = int(row % dims.y);
      const int z = int(row / dims.y);
      float* out = texels + std::int64_t(dims.x) * row;
      for (int x = 0; x < dims.x; ++x) out[x] = visibility(view.world_from_index(vec3(x, y, z)));
    }
  });
  return cache;
}

// One cache per light, and the parameters they were built with, for the SAT
// techniques' optional shadow cache. A light without a cache (an environment
// light, or one the technique has no table for) has an empty view.
class LightVisibilityCaches {
 public:
  // Built, and for these parameters (the caller leaves out those that only
  // rebuild what the caches are made from, which clears them).
  bool current(const ParameterValues& params) const { return built_ && params == params_; }
  bool built() const { return built_; }

  // For each light i < light_count with has_cache(i): a cache of `dims` over
  // `box` holding visibility(i, world).
  template <class HasCache, class Visibility>
  void build(std::size_t light_count, const Box3& box, ivec3 dims, const ParameterValues& params,
             const HasCache& has_cache, const Visibility& visibility) {
    clear();  // before building: the old caches' memory is free for the new ones
    views_.assign(light_count, VolumeView{});
    for (std::size_t i = 0; i < light_count; ++i) {
      if (!has_cache(i)) continue;
      caches_.push_back(build_visibility_cache(box, dims, [&](vec3 p) { return visibility(i, p); }));
      views_[i] = caches_.back().view();
    }
    built_ = true;
    params_ = params;
  }

  void clear() {
    caches_.clear();
    views_.clear();
    built_ = false;
  }

  const VolumeView* views() const { return views_.data(); }
  std::uint64_t bytes() const {
    std::uint64_t total = 0;
    for (const Volume& c : caches_) total += c.total_bytes();
    return total;
  }

 private:
  std::vector<Volume> caches_;
  std::vector<VolumeView> views_;  // one per light
  bool built_ = false;
  ParameterValues params_;
};

}  // namespace penumbra

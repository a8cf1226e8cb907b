#pragma once
// The shadow cache of Ament et al. 2014, Algorithm 1: a float grid over the
// volume's world box holding one light's visibility per texel, so that
// rendering reads one trilinear sample instead of evaluating the tables per
// viewing-ray sample. Texel (0, 0, 0) sits on the box's lower corner and the
// last texel on its upper corner (the layout of shadow-rays' cache).
#include "penumbra/base/parallel.h"
#include "penumbra/techniques/sat_common/batch.h"
#include "penumbra/render/parameters.h"
#include "penumbra/volume/volume.h"

#include <cstdint>
#include <optional>
#include <vector>

namespace penumbra {

// Texels per axis for a volume of `data_dims` at `resolution` texels per
// voxel (at least 2 per axis).
ivec3 visibility_cache_dims(ivec3 data_dims, float resolution);

// A cache of `dims` texels over `box` with texel value visibility(world);
// visibility may also be a batch (sat_common/batch.h).
template <class Visibility> Volume build_visibility_cache(const Box3& box, ivec3 dims, const Visibility& visibility) {
  Volume cache(dims, VoxelType::Float32);
  cache.set_spacing(glm::max(box.extent() / vec3(dims - 1), vec3(1e-6f)));
  cache.set_origin(box.lower);
  const VolumeView view = cache.view();
  const std::int64_t row = dims.x, slab = std::int64_t(dims.x) * dims.y;
  evaluate_batch(
      visibility, slab * dims.z,
      [&](std::int64_t t) {
        return view.world_from_index(vec3(float(t % row), float(t % slab / row), float(t / slab)));
      },
      cache.frame_as<float>(0));
  return cache;
}

// Visibility grids may also be kept in 16-bit (filtered-sat's, issue 22):
// texel = round(65535 v), a step of 1.5e-5 (at most 0.007 L* where the
// visibility is that small, where lightness is linear in it: 903.3 Y).
inline constexpr float kUnorm16Step = 1.0f / 65535.0f;
// `cache` (a float visibility grid from build_visibility_cache) in 16-bit,
// with the same geometry.
Volume unorm16_visibility(const Volume& cache);

// One cache per light, and the parameters they were built with, for the SAT
// techniques' optional shadow cache. A light without a cache (an environment
// light, or one the technique has no table for) has an empty view. Caches are
// rebuilt per light: a light whose own inputs did not change keeps its cache.
class LightVisibilityCaches {
 public:
  // Built, and for these parameters (the caller leaves out those that only
  // rebuild what the caches are made from, which clears them).
  bool current(const ParameterValues& params) const { return built_ && params == params_; }
  bool built() const { return built_; }
  // Keep the caches in 16-bit (unorm16_visibility) once after_build ran
  // (which sees the float cache); the views then hold uint16 texels.
  void set_unorm16(bool unorm16) { unorm16_ = unorm16; }

  // For each light i < light_count with has_cache(i): a cache of `dims` over
  // `box` holding visibility(i, world) (or the batch visibility(i, count,
  // point, out), sat_common/batch.h), rebuilt when the parameters, the box
  // or the dims changed, when the light had none, or when stale(i) (its own
  // inputs changed). Caches of lights without one are released first, then
  // each stale cache before its replacement is built; before_build(i) runs
  // just before light i's cache is built (to build what visibility(i, .)
  // reads, one light at a time). Returns how many caches it built.
  template <class HasCache, class Stale, class Visibility>
  int update(std::size_t light_count, const Box3& box, ivec3 dims, const ParameterValues& params,
             const HasCache& has_cache, const Stale& stale, const Visibility& visibility) {
    return update(light_count, box, dims, params, has_cache, stale, visibility, [](std::size_t) {});
  }
  template <class HasCache, class Stale, class Visibility, class BeforeBuild>
  int update(std::size_t light_count, const Box3& box, ivec3 dims, const ParameterValues& params,
             const HasCache& has_cache, const Stale& stale, const Visibility& visibility,
             const BeforeBuild& before_build) {
    return update(light_count, box, dims, params, has_cache, stale, visibility, before_build,
                  [](std::size_t, const Volume&) {});
  }
  // after_build(i, cache) runs just after light i's cache is built, while
  // what before_build(i) built still lives (filtered-sat's refined cells).
  template <class HasCache, class Stale, class Visibility, class BeforeBuild, class AfterBuild>
  int update(std::size_t light_count, const Box3& box, ivec3 dims, const ParameterValues& params,
             const HasCache& has_cache, const Stale& stale, const Visibility& visibility,
             const BeforeBuild& before_build, const AfterBuild& after_build) {
    const bool all = !built_ || unorm16_ != built_unorm16_ || !(params == params_) || dims != dims_ ||
                     box.lower != box_.lower || box.upper != box_.upper;
    caches_.resize(light_count);
    for (std::size_t i = 0; i < light_count; ++i) {
      if (!has_cache(i)) caches_[i].reset();
    }
    int count = 0;
    for (std::size_t i = 0; i < light_count; ++i) {
      if (!has_cache(i) || (caches_[i] && !all && !stale(i))) continue;
      caches_[i].reset();  // free the old cache first
      before_build(i);
      caches_[i].emplace(build_visibility_cache(box, dims, [&](std::int64_t count, const auto& point, float* out) {
        evaluate_light_batch(visibility, i, count, point, out);
      }));
      after_build(i, *caches_[i]);
      if (unorm16_) {
        Volume compact = unorm16_visibility(*caches_[i]);
        caches_[i].emplace(std::move(compact));
      }
      ++count;
    }
    views_.assign(light_count, VolumeView{});
    for (std::size_t i = 0; i < light_count; ++i) {
      if (caches_[i]) views_[i] = caches_[i]->view();
    }
    built_ = true;
    built_unorm16_ = unorm16_;
    params_ = params;
    dims_ = dims;
    box_ = box;
    return count;
  }

  void clear() {
    caches_.clear();
    views_.clear();
    built_ = false;
  }

  const VolumeView* views() const { return views_.data(); }
  ivec3 dims() const { return dims_; }  // every light's grid
  std::uint64_t bytes() const {
    std::uint64_t total = 0;
    for (const auto& c : caches_) total += c ? c->total_bytes() : 0;
    return total;
  }

 private:
  std::vector<std::optional<Volume>> caches_;  // one per light
  std::vector<VolumeView> views_;              // one per light
  bool built_ = false;
  bool unorm16_ = false, built_unorm16_ = false;
  ParameterValues params_;
  ivec3 dims_{0};
  Box3 box_;
};

}  // namespace penumbra

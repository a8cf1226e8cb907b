#include "penumbra/techniques/shadow_rays/shadow_rays.h"

#include "penumbra/render/mesh_march.h"
#include "penumbra/render/render_lit.h"
#include "penumbra/render/scene_resources.h"
#include "penumbra/techniques/shadow_rays/shadow_cache.h"
#include "penumbra/techniques/shadow_rays/shadow_ray_visibility.h"

#include <algorithm>
#include <vector>

namespace penumbra {
namespace {

class ShadowRays final : public Technique {
 public:
  void prepare(const Scene& scene, const ParameterValues& params) override {
    const bool shared_changed = resources_.update(scene, scene.material().shading == Shading::Phong);
    meshes_.update(scene);
    meshes_.build_shapes();
    density_scale_ = float(params.number("shadow_density_scale"));
    light_samples_ = params.integer("light_samples");
    use_cache_ = params.flag("shadow_cache");
    if (!use_cache_) {
      caches_.clear();
      cache_views_.clear();
      return;
    }
    const SceneVersions& v = scene.versions();
    const bool stale = shared_changed || caches_.empty() || v.lights != lights_version_ ||
                       v.geometry != geometry_version_ || !(params == cache_params_);
    if (!stale) return;
    const RenderView view = resources_.shadow_view(scene);
    caches_.clear();
    cache_views_.clear();
    for (int i = 0; i < view.light_count; ++i) {
      caches_.push_back(
          build_shadow_cache(view, i, density_scale_, light_samples_, float(params.number("cache_resolution"))));
    }
    for (const Volume& c : caches_) cache_views_.push_back(c.view());
    lights_version_ = v.lights;
    geometry_version_ = v.geometry;
    cache_params_ = params;
    ++rebuilds_;
  }

  void render(const Scene& scene, Image& image, RenderStats* stats) override {
    RenderView view = resources_.view(scene);
    view.structures = rebuilds_;  // the caches' version, for device mirrors
    const RenderView shadows = resources_.shadow_view(scene);
    const Shading shading = scene.material().shading;
    ShadowRayVisibility rays{&shadows, density_scale_, light_samples_};
    if (!meshes_.empty()) {
      rays.meshes = meshes_.view();
      rays.mesh_step = meshes_.sampling_step(view.step);
      const MeshMarch march{rays.meshes, rays.mesh_step, meshes_.min_step(),
                            has_extinction(view) || has_extinction(shadows)};
      if (use_cache_) {
        render_meshes(view, march, CachedShadowRayVisibility{rays, cache_views_.data()}, shading, image, stats);
      } else {
        render_meshes(view, march, rays, shading, image, stats);
      }
      return;
    }
    if (use_cache_) {
      render_lit(view, CachedShadowRayVisibility{rays, cache_views_.data()}, shading, image, stats);
    } else {
      render_lit(view, rays, shading, image, stats);
    }
  }

  std::uint64_t rebuilds() const override { return rebuilds_; }

  std::uint64_t aux_bytes() const override {
    std::uint64_t bytes = meshes_.bytes();
    for (const Volume& c : caches_) bytes += c.total_bytes();
    return bytes;
  }

 private:
  // Whether any macrocell of the view can have extinction.
  bool has_extinction(const RenderView& v) const {
    const std::size_t cells = resources_.majorants().majorant.size();
    return v.majorants && std::any_of(v.majorants, v.majorants + cells, [](float x) { return x > 0.0f; });
  }

  // The volume (with the scene's shading) and the meshes (with the phase
  // function) marched together per ray (render/mesh_march.h), on the CPU.
  template <class Visibility>
  static void render_meshes(const RenderView& view, const MeshMarch& march, const Visibility& visibility,
                            Shading shading, Image& image, RenderStats* stats) {
    render_image_with_meshes(view, march, ScatteringLighting<Visibility>{&view, visibility, shading},
                             ScatteringLighting<Visibility>{&view, visibility, Shading::Phase}, image, stats);
  }

  SceneResources resources_;
  MeshMedia meshes_;  // the scene's meshes as media, with their BVHs
  float density_scale_ = 1.0f;
  int light_samples_ = 1;
  bool use_cache_ = false;
  std::vector<Volume> caches_;
  std::vector<VolumeView> cache_views_;
  std::uint64_t lights_version_ = 0;
  std::uint64_t geometry_version_ = 0;
  ParameterValues cache_params_;
  std::uint64_t rebuilds_ = 0;
};

}  // namespace

TechniqueInfo shadow_rays_info() {
  return TechniqueInfo{
      "shadow-rays",
      "single scattering with shadow-ray transmittance per light (the hard-shadow reference)",
      ParameterTable{{
          ParameterSpec::real("shadow_density_scale", 1.0, 0.0, 100.0,
                              "multiplies sigma_t along shadow rays only (0 = unshadowed)"),
          ParameterSpec::integer("light_samples", 1, 1, 1024,
                                 "shadow rays per area light (stratified, seeded); 1 = one ray to its centre"),
          ParameterSpec::flag("shadow_cache", false,
                              "precompute transmittance per light on a grid instead of marching per sample"),
          ParameterSpec::real("cache_resolution", 0.5, 0.05, 2.0,
                              "shadow cache grid size as a fraction of the data grid"),
      }},
      [] { return std::make_unique<ShadowRays>(); },
      /*draws_meshes=*/true};
}

}  // namespace penumbra

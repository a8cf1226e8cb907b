#include "penumbra/techniques/occlusion_map/occlusion_map.h"

#include "penumbra/base/error.h"
#include "penumbra/render/scene_resources.h"
#include "penumbra/techniques/occlusion_map/iso_occupancy.h"
#include "penumbra/techniques/occlusion_map/isosurface_render.h"
#include "penumbra/techniques/occlusion_map/moment_pyramid.h"
#include "penumbra/techniques/sat_common/table_dependencies.h"
#include "penumbra/techniques/sat_common/visibility_cache.h"

#include <optional>

namespace penumbra {
namespace {

// The angular radius of directional and point lights when light_size_deg is
// unset (its default before issue 18).
constexpr float kDefaultLightSizeDeg = 3.0f;

ShadowMode shadow_mode(const std::string& name) {
  if (name == "hard") return ShadowMode::Hard;
  if (name == "soft") return ShadowMode::Soft;
  return ShadowMode::None;
}

class OcclusionMap final : public Technique {
 public:
  void prepare(const Scene& scene, const ParameterValues& params) override {
    dvr_ = params.choice("mode") == "dvr";
    resources_.update(scene, dvr_ && scene.material().shading == Shading::Phong);
    MomentPyramidSettings settings;
    settings.moments = params.integer("moments");
    settings.resolution = float(params.number("resolution"));
    settings.kernel_size = params.integer("kernel_size");
    settings.validate();

    const std::uint64_t data_version = scene.versions().data;
    const bool data_changed = data_version != data_version_;
    if (data_changed || pyramid_.empty() || !(settings == pyramid_.settings()) ||
        scene.clip_planes() != pyramid_.clip_planes()) {
      const ValueRange range = scene.volume().value_range();
      dvr_shadows_.clear();  // marched through the old pyramid
      pyramid_ = MomentPyramid(scene.volume_view(), vec2(range.min, range.max), settings, scene.clip_planes());
      data_version_ = data_version;
      ++rebuilds_;
    }
    const vec2 tf_range = scene.tf_value_range();
    iso_ = tf_range.x + float(params.number("iso_value")) * (tf_range.y - tf_range.x);
    if (data_changed || !occupancy_ || occupancy_->iso_value() != iso_) {
      occupancy_.emplace(resources_.macrocells(), iso_);
    }
    shadows_ = shadow_mode(params.choice("shadows"));
    if (dvr_ && shadows_ == ShadowMode::Hard) {
      throw InvalidArgument("shadows", "mode dvr has soft shadows or none; hard shadows (iso-test rays) need mode iso");
    }
    ambient_occlusion_ = params.flag("ambient_occlusion");
    const std::string& combine = params.choice("ao_combine");
    ao_combine_ = combine == "mean" ? AoCombine::Mean : (combine == "product" ? AoCombine::Product : AoCombine::Max);
    ao_offset_ = float(params.number("ao_offset"));
    ao_on_lights_ = params.flag("ao_lights");
    const float size = float(params.number("light_size_deg"));
    default_spread_ = std::tan(glm::radians(size < 0.0f ? kDefaultLightSizeDeg : size));
    forced_spread_ = size < 0.0f ? -1.0f : default_spread_;
    update_dvr_shadows(scene, params);
  }

  void render(const Scene& scene, Image& image, RenderStats* stats) override {
    if (pyramid_.moments() == 4) {
      render_with<4>(scene, image, stats);
    } else {
      render_with<2>(scene, image, stats);
    }
  }

  std::uint64_t aux_bytes() const override {
    return pyramid_.bytes() + (occupancy_ ? occupancy_->bytes() : 0) + dvr_shadows_.bytes();
  }
  // Builds of the moment pyramid and of DVR mode's shadow grids, one per
  // light (the iso flag grid is not counted: it is rebuilt with the iso-value
  // by design and costs microseconds).
  std::uint64_t rebuilds() const override { return rebuilds_; }

 private:
  template <int K> OcclusionQueries<K> queries(const Box3& box) const {
    OcclusionQueries<K> q;
    q.pyramid = pyramid_.view<K>();
    q.box = box;
    q.ao_offset = ao_offset_;
    q.ao_combine = ao_combine_;
    q.default_spread = default_spread_;
    q.forced_spread = forced_spread_;
    return q;
  }
  ValueNormalisation normalisation() const {
    const vec2 range = pyramid_.value_range();
    return ValueNormalisation{range.x, range.y > range.x ? 1.0f / (range.y - range.x) : 1.0f};
  }

  // DVR mode's soft shadows: one grid per light over the volume's box, at the
  // map's level-0 resolution, each node marched once (occlusion_shading.h,
  // dvr_soft_shadow_query). A grid is rebuilt when its light moves or changes
  // size, or when the pyramid, the iso-value or the march's parameters
  // change; a TF or camera change keeps it.
  void update_dvr_shadows(const Scene& scene, const ParameterValues& params) {
    if (!dvr_ || shadows_ != ShadowMode::Soft) {
      dvr_shadows_.clear();
      return;
    }
    ParameterValues key = params;
    for (const char* name : {"ambient_occlusion", "ao_combine", "ao_lights"}) {
      key.set(name, params.table().at(name).default_value);
    }
    const std::vector<Light>& lights = scene.lights();
    std::vector<LightPlacement> placements = light_placements(lights);
    std::vector<vec4> sizes;
    for (const Light& l : lights) sizes.push_back(vec4(l.angle_deg, l.spread_y_deg(), l.radius, float(l.profile)));
    if (dvr_shadows_.current(key) && placements == dvr_placements_ && sizes == dvr_sizes_ && iso_ == dvr_iso_) {
      return;
    }
    if (iso_ != dvr_iso_) dvr_shadows_.clear();
    const VolumeView volume = scene.volume_view();
    const Box3 box = scene.volume().world_box();
    const AnyVoxelSampler sampler(volume.data, volume.dims, volume.type);
    const ValueNormalisation normalise = normalisation();
    const float t = normalise(iso_);
    const auto build = [&](const auto& visibility) {
      return dvr_shadows_.update(
          lights.size(), box, visibility_cache_dims(volume.dims, float(params.number("resolution"))), key,
          [&](std::size_t i) { return lights[i].type != LightType::Environment; },
          [&](std::size_t i) {
            return i >= dvr_placements_.size() || !(placements[i] == dvr_placements_[i]) || sizes[i] != dvr_sizes_[i];
          },
          visibility);
    };
    const auto query = [&](const auto& q, std::size_t light, vec3 p) {
      return dvr_soft_shadow_query(q, volume, sampler, normalise, lights[light], p);
    };
    const OcclusionQueries<2> q2 = queries<2>(box);
    const SoftShadowMarch march = q2.packets_fit() ? soft_shadow_march(active_simd_target()) : nullptr;
    if (pyramid_.moments() == 4) {
      const OcclusionQueries<4> q4 = queries<4>(box);
      rebuilds_ += std::uint64_t(build([&](std::size_t i, vec3 p) { return soft_shadow(q4, query(q4, i, p), t); }));
    } else if (!march) {
      rebuilds_ += std::uint64_t(build([&](std::size_t i, vec3 p) { return soft_shadow(q2, query(q2, i, p), t); }));
    } else {
      // The nodes' marches as SIMD packets (soft_shadow_batch.h), a few thousand at a time.
      rebuilds_ += std::uint64_t(build([&](std::size_t i, std::int64_t count, const auto& point, float* out) {
        constexpr std::int64_t kChunk = 4096;
        parallel_for(0, (count + kChunk - 1) / kChunk, [&](std::int64_t first, std::int64_t last) {
          SoftShadowBatch batch(int(kChunk), 1);
          for (std::int64_t c = first; c < last; ++c) {
            const std::int64_t begin = c * kChunk, end = std::min(count, begin + kChunk);
            SoftShadowQueries marches = batch.queries();
            for (std::int64_t n = begin; n < end; ++n) {
              const SoftShadowQuery s = query(q2, i, point(n));
              marches.record(s.p, s.n, s.to_light, s.distance, s.spread, s.own);
            }
            SoftShadowBatch::pad(marches);
            march(q2, t, marches, batch.visibility());
            std::copy(batch.visibility(), batch.visibility() + (end - begin), out + begin);
          }
        }, 1);
      }));
    }
    dvr_placements_ = std::move(placements);
    dvr_sizes_ = std::move(sizes);
    dvr_iso_ = iso_;
  }

  template <int K> void render_with(const Scene& scene, Image& image, RenderStats* stats) const {
    RenderView lit = resources_.view(scene);
    const float ambient = lit.material.ambient;
    lit.material.ambient = 0.0f;
    const RenderView iso_view = occupancy_->apply(lit);
    OcclusionShadingSetup<K> setup;
    setup.lit_view = &lit;
    setup.iso_view = &iso_view;
    setup.queries = queries<K>(lit.box);
    setup.normalise = normalisation();
    setup.iso = iso_;
    setup.iso_color = vec3(lit.tf.lookup(iso_));
    setup.ambient = ambient;
    setup.shadows = shadows_;
    setup.ambient_occlusion = ambient_occlusion_;
    setup.ao_on_lights = ao_on_lights_;
    if (!dvr_) {
      render_isosurface_image(setup, image, stats);
      return;
    }
    if (active_device() == Device::Cuda) note_cpu_fallback("occlusion-map in mode dvr");
    const Shading shading = scene.material().shading;
    const VolumeView* grids = dvr_shadows_.built() ? dvr_shadows_.views() : nullptr;
    if constexpr (K == 2) {
      // Packets (occlusion_map_packets.cpp) read the volume through
      // AnyVoxelSampler; one lighting type serves every voxel type.
      if (dvr_packets_fit(setup.queries, lit)) {
        const AnyVoxelSampler any(lit.volume.data, lit.volume.dims, lit.volume.type);
        render_image(
            lit, [&](const auto&) { return DvrOcclusionLighting<2, AnyVoxelSampler>{&setup, any, shading, grids}; },
            image, stats);
        return;
      }
    }
    render_image(
        lit,
        [&](const auto& sampler) {
          return DvrOcclusionLighting<K, std::decay_t<decltype(sampler)>>{&setup, sampler, shading, grids};
        },
        image, stats);
  }

  // Whether DVR mode's samples can be lit as packets: a SIMD target for this
  // view, and 32-bit gather offsets that reach every node of the pyramid and
  // every byte of the shadow grids.
  bool dvr_packets_fit(const OcclusionQueries<2>& queries, const RenderView& view) const {
    if (packet_target(view) == SimdTarget::Scalar || !queries.packets_fit()) return false;
    constexpr std::uint64_t limit = (std::uint64_t(1) << 31) - 64;
    const ivec3 d = dvr_shadows_.dims();
    return !dvr_shadows_.built() || std::uint64_t(d.x) * std::uint64_t(d.y) * std::uint64_t(d.z) * 4 < limit;
  }

  SceneResources resources_;
  MomentPyramid pyramid_;
  std::optional<IsoOccupancy> occupancy_;
  LightVisibilityCaches dvr_shadows_;  // mode dvr, soft shadows: one grid per light
  std::vector<LightPlacement> dvr_placements_;  // what they were built for
  std::vector<vec4> dvr_sizes_;
  float dvr_iso_ = 0.0f;
  std::uint64_t data_version_ = 0;
  std::uint64_t rebuilds_ = 0;
  bool dvr_ = false;
  float iso_ = 0.0f;
  ShadowMode shadows_ = ShadowMode::Soft;
  bool ambient_occlusion_ = true;
  AoCombine ao_combine_ = AoCombine::Product;
  float ao_offset_ = 2.0f;
  bool ao_on_lights_ = true;
  float default_spread_ = 0.0f;
  float forced_spread_ = -1.0f;
};

}  // namespace

TechniqueInfo occlusion_map_info() {
  return TechniqueInfo{
      "occlusion-map",
      "isosurface ray casting with ambient occlusion and soft shadows from a moment pyramid (Penner & Mitchell 2008)",
      ParameterTable{{
          ParameterSpec::real("iso_value", 0.5, 0.0, 1.0,
                              "iso-value normalised to the TF range (0 = range min, 1 = range max)"),
          ParameterSpec::choice("mode", "iso", {"iso", "dvr"},
                                "iso: isosurface ray casting; dvr: DVR with the same ambient occlusion (Fig. 11) and "
                                "soft shadows from a grid per light"),
          ParameterSpec::choice("shadows", "soft", {"none", "hard", "soft"},
                                "none, hard (iso-test ray; mode iso only) or soft (occlusion-map march; in mode dvr "
                                "marched once per grid node)"),
          ParameterSpec::flag("ambient_occlusion", true, "ambient occlusion from four pyramid levels along the normal"),
          ParameterSpec::choice("ao_combine", "product", {"max", "mean", "product"},
                                "combine the four levels' occlusion: max (the paper), mean, or product of the "
                                "unoccluded fractions"),
          ParameterSpec::real("ao_offset", 2.0, 0.0, 8.0,
                              "AO sample distance from the surface, in Gaussian sigmas of each level"),
          ParameterSpec::flag("ao_lights", true, "AO also darkens the lights, not only the ambient term"),
          ParameterSpec::real("light_size_deg", -1.0, -1.0, 45.0,
                              "angular radius of every light for soft shadows (< 0 = each light's own size; "
                              "3 for directional and point lights)"),
          ParameterSpec::integer("moments", 2, 2, 4, "2 (Chebyshev bound, the paper) or 4 (Hamburger bound)"),
          ParameterSpec::real("resolution", 0.5, 0.125, 1.0, "occlusion map level 0 as a fraction of the data grid"),
          ParameterSpec::integer("kernel_size", 5, 3, 15, "taps of level 0's Gaussian at level-0 resolution (odd)"),
      }},
      [] { return std::make_unique<OcclusionMap>(); }};
}

}  // namespace penumbra

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

// A sample in the one-voxel ramp at a solid's surface interpolates between
// the surface's nodes and the solid's homogeneous interior, whose nodes have
// no AO of their own (a sample there takes 1, which would brighten the
// surface). Each such node takes the mean of its oriented neighbours among
// the 26 around it, or 1 where it has none.
void fill_unoriented_nodes(Volume& grid) {
  const ivec3 d = grid.dims();
  float* texels = grid.frame_as<float>(0);
  const std::vector<float> baked(texels, texels + std::int64_t(d.x) * d.y * d.z);
  const auto at = [&](int x, int y, int z) { return baked[std::size_t((std::int64_t(z) * d.y + y) * d.x + x)]; };
  parallel_for(0, d.z, [&](std::int64_t first, std::int64_t last) {
    for (int z = int(first); z < int(last); ++z) {
      for (int y = 0; y < d.y; ++y) {
        for (int x = 0; x < d.x; ++x) {
          if (at(x, y, z) != kDvrGridNode.unoriented) continue;
          float sum = 0.0f;
          int count = 0;
          for (int k = std::max(z - 1, 0); k <= std::min(z + 1, d.z - 1); ++k)
            for (int j = std::max(y - 1, 0); j <= std::min(y + 1, d.y - 1); ++j)
              for (int i = std::max(x - 1, 0); i <= std::min(x + 1, d.x - 1); ++i) {
                const float v = at(i, j, k);
                if (v != kDvrGridNode.unoriented) sum += v, ++count;
              }
          texels[(std::int64_t(z) * d.y + y) * d.x + x] = count > 0 ? sum / float(count) : 1.0f;
        }
      }
    }
  });
}

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
      ambient_grid_.reset();  // read the old pyramid
      ++pyramid_builds_;
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
    update_plane_shadows(scene);
    update_dvr_ambient(scene, params.choice("dvr_ao") == "grid");
  }

  void render(const Scene& scene, Image& image, RenderStats* stats) override {
    if (pyramid_.moments() == 4) {
      render_with<4>(scene, image, stats);
    } else {
      render_with<2>(scene, image, stats);
    }
  }

  std::uint64_t aux_bytes() const override {
    return pyramid_.bytes() + (occupancy_ ? occupancy_->bytes() : 0) + dvr_shadows_.bytes() + plane_shadows_.bytes() +
           (ambient_grid_ ? ambient_grid_->total_bytes() : 0);
  }
  // Builds of the moment pyramid, of DVR mode's shadow grids, one per
  // light, and of its AO grid (the iso flag grid is not counted: it is rebuilt with the iso-value
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
    for (const char* name : {"ambient_occlusion", "ao_combine", "ao_lights", "dvr_ao"}) {
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
    if (pyramid_.moments() == 4) {
      const OcclusionQueries<4> q4 = queries<4>(box);
      rebuilds_ += std::uint64_t(build([&](std::size_t i, vec3 p) { return soft_shadow(q4, query(q4, i, p), t); }));
    } else {
      const OcclusionQueries<2> q2 = queries<2>(box);
      rebuilds_ += std::uint64_t(build([&](std::size_t i, std::int64_t count, const auto& point, float* out) {
        march_queries(q2, t, count, [&](std::int64_t n) { return query(q2, i, point(n)); }, out);
      }));
    }
    dvr_placements_ = std::move(placements);
    dvr_sizes_ = std::move(sizes);
    dvr_iso_ = iso_;
  }

  // out[n] = the soft shadow of query(n) for n < count, two moments: as SIMD
  // packets (soft_shadow_batch.h) a few thousand at a time, or one by one
  // where packets do not fit.
  template <class Query>
  static void march_queries(const OcclusionQueries<2>& q, float t, std::int64_t count, const Query& query,
                            float* out) {
    const SoftShadowMarch march = q.packets_fit() ? soft_shadow_march(active_simd_target()) : nullptr;
    constexpr std::int64_t kChunk = 4096;
    parallel_for(0, (count + kChunk - 1) / kChunk, [&](std::int64_t first, std::int64_t last) {
      std::optional<SoftShadowBatch> batch;
      if (march) batch.emplace(int(kChunk), 1);
      for (std::int64_t c = first; c < last; ++c) {
        const std::int64_t begin = c * kChunk, end = std::min(count, begin + kChunk);
        if (!march) {
          for (std::int64_t n = begin; n < end; ++n) out[n] = soft_shadow(q, query(n), t);
          continue;
        }
        SoftShadowQueries marches = batch->queries();
        for (std::int64_t n = begin; n < end; ++n) {
          const SoftShadowQuery s = query(n);
          marches.record(s.p, s.n, s.to_light, s.distance, s.spread, s.own);
        }
        SoftShadowBatch::pad(marches);
        march(q, t, marches, batch->visibility());
        std::copy(batch->visibility(), batch->visibility() + (end - begin), out + begin);
      }
    }, 1);
  }

  // Soft shadows on the opaque planes (both modes): per light and plane a
  // grid over the plane's region the volume can shadow
  // (sat_common/plane_caches.h), one node per voxel, each node marched once
  // as the plane's pixels would be. The march starts lifted off the plane
  // (ao_offset sigma0) and only where its axis meets the volume's box, so the
  // region is that of the box grown by the lift. Rebuilt when the planes or
  // the lights move, or when what the march reads changes (the pyramid, the
  // iso-value, the lights' sizes, light_size_deg, ao_offset).
  void update_plane_shadows(const Scene& scene) {
    if (shadows_ != ShadowMode::Soft || scene.planes().empty()) {
      plane_shadows_.clear();
      return;
    }
    const std::vector<Light>& lights = scene.lights();
    const std::vector<Plane>& planes = scene.planes();
    std::vector<float> inputs{float(pyramid_builds_), iso_, ao_offset_, default_spread_, forced_spread_};
    for (const Light& l : lights) inputs.insert(inputs.end(), {l.angle_deg, l.spread_y_deg(), l.radius});
    if (inputs != plane_inputs_) {
      plane_inputs_ = std::move(inputs);
      ++plane_version_;
    }
    const Box3 box = scene.volume().world_box();
    const float lift = ao_offset_ * pyramid_.view<2>().sigma0;
    const Box3 reach{box.lower - vec3(lift), box.upper + vec3(lift)};
    const float t = normalisation()(iso_);
    // The plane a node lies on: the nearest (nodes lie on their plane).
    const auto plane_of = [&](vec3 p) -> const Plane& {
      std::size_t best = 0;
      float best_distance = kInfinity;
      for (std::size_t k = 0; k < planes.size(); ++k) {
        const float d = std::abs(glm::dot(p - planes[k].point, planes[k].normal));
        if (d < best_distance) best_distance = d, best = k;
      }
      return planes[best];
    };
    const float cell = scene.volume().view().min_spacing();
    if (pyramid_.moments() == 4) {
      const OcclusionQueries<4> q4 = queries<4>(box);
      plane_builds_ += std::uint64_t(plane_shadows_.update(lights, planes, reach, cell, plane_version_, [&](int i, vec3 p) {
        return soft_shadow(q4, plane_soft_shadow_query(q4, lights[std::size_t(i)], plane_of(p), p), t);
      }));
    } else {
      const OcclusionQueries<2> q2 = queries<2>(box);
      plane_builds_ += std::uint64_t(plane_shadows_.update(
          lights, planes, reach, cell, plane_version_,
          [&](std::size_t i, std::int64_t count, const auto& point, float* out) {
            march_queries(q2, t, count, [&](std::int64_t n) {
              const vec3 p = point(n);
              return plane_soft_shadow_query(q2, lights[i], plane_of(p), p);
            }, out);
          }));
    }
  }

  // DVR mode's AO grid (dvr_ao=grid): dvr_ambient at every voxel of the data
  // grid (the grid's nodes are the voxels), kept in 16 bits, built when the pyramid or the AO
  // parameters change; the iso-value, the TF, the lights and the camera keep
  // it (the AO query is each sample's own value).
  void update_dvr_ambient(const Scene& scene, bool grid) {
    if (!dvr_ || !ambient_occlusion_ || !grid) {
      ambient_grid_.reset();
      return;
    }
    const vec2 key(float(int(ao_combine_)), ao_offset_);
    if (ambient_grid_ && key == ambient_key_) return;
    ambient_grid_.reset();
    const RenderView view = resources_.view(scene);
    const VolumeView& volume = view.volume;
    const Box3 box = scene.volume().world_box();
    const ValueNormalisation normalise = normalisation();
    const AnyVoxelSampler sampler(volume.data, volume.dims, volume.type);
    const auto scalar = [&](const auto& q) {
      return build_visibility_cache(box, volume.dims, [&](vec3 p) {
        const vec3 index = volume.index_from_world(p);
        return dvr_ambient<ScalarLanes>(q, normalise, volume, sampler, index, p, sampler(index), true, kDvrGridNode);
      });
    };
    const OcclusionQueries<2> q2 = queries<2>(box);
    const DvrAmbientBatch batch =
        pyramid_.moments() == 2 && q2.packets_fit() && packet_target(view) != SimdTarget::Scalar
            ? simd_unit_function(packet_target(view), []<SimdTarget T>() { return &dvr_ambient_batch<T>; })
            : nullptr;
    if (pyramid_.moments() == 4) {
      ambient_grid_.emplace(scalar(queries<4>(box)));
    } else if (!batch) {
      ambient_grid_.emplace(scalar(q2));
    } else {
      // The nodes as SIMD packets, a few thousand at a time.
      ambient_grid_.emplace(build_visibility_cache(box, volume.dims, [&](std::int64_t count, const auto& point,
                                                                         float* out) {
        constexpr int kChunk = 4096;
        parallel_for(0, (count + kChunk - 1) / kChunk, [&](std::int64_t first, std::int64_t last) {
          std::vector<float> xyz(3 * (kChunk + 16)), values(kChunk + 16);
          float* fields[3] = {xyz.data(), xyz.data() + kChunk + 16, xyz.data() + 2 * (kChunk + 16)};
          for (std::int64_t c = first; c < last; ++c) {
            const std::int64_t begin = c * kChunk, end = std::min(count, begin + kChunk);
            const int n = int(end - begin);
            for (int i = 0; i < (n + 15) / 16 * 16; ++i) {
              const vec3 p = point(begin + std::min(i, n - 1));  // padding repeats the last node
              for (int a = 0; a < 3; ++a) fields[a][i] = p[a];
            }
            batch(q2, normalise, volume, fields, n, values.data());
            std::copy(values.data(), values.data() + n, out + begin);
          }
        }, 1);
      }));
    }
    fill_unoriented_nodes(*ambient_grid_);
    Volume compact = unorm16_visibility(*ambient_grid_);  // half the bytes; steps of 1.5e-5
    ambient_grid_.emplace(std::move(compact));
    ambient_key_ = key;
    ++rebuilds_;
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
    if (shadows_ == ShadowMode::Soft) setup.plane_shadows = plane_shadows_.view();
    lit.structures = rebuilds_ + plane_builds_;  // the pyramid's and grids' version, for device mirrors
    if (!dvr_) {
      render_isosurface_image(setup, image, stats);
      return;
    }
    const Shading shading = scene.material().shading;
    const VolumeView* grids = dvr_shadows_.built() ? dvr_shadows_.views() : nullptr;
    const VolumeView ao_grid = ambient_grid_ ? ambient_grid_->view() : VolumeView{};
    // The CUDA device (occlusion_map_device.cu) and the packets
    // (occlusion_map_packets.cpp) read the volume through AnyVoxelSampler;
    // one lighting type serves every voxel type.
    bool any_voxel = active_device() == Device::Cuda;
    if constexpr (K == 2) any_voxel = any_voxel || dvr_packets_fit(setup.queries, lit);
    if (any_voxel) {
      const AnyVoxelSampler any(lit.volume.data, lit.volume.dims, lit.volume.type);
      const DvrOcclusionLighting<K, AnyVoxelSampler> lighting{&setup, any, shading, grids, ao_grid, kUnorm16Step};
      render_image(lit, [&](const auto&) { return lighting; }, image, stats);
      return;
    }
    render_image(
        lit,
        [&](const auto& sampler) {
          using Sampler = std::decay_t<decltype(sampler)>;
          return DvrOcclusionLighting<K, Sampler>{&setup, sampler, shading, grids, ao_grid, kUnorm16Step};
        },
        image, stats);
  }

  // Whether DVR mode's samples can be lit as packets: a SIMD target for this
  // view, and 32-bit gather offsets that reach every node of the pyramid and
  // every byte of the shadow grids and the AO grid.
  bool dvr_packets_fit(const OcclusionQueries<2>& queries, const RenderView& view) const {
    if (packet_target(view) == SimdTarget::Scalar || !queries.packets_fit()) return false;
    constexpr std::uint64_t limit = (std::uint64_t(1) << 31) - 64;
    const ivec3 d = dvr_shadows_.dims();
    if (ambient_grid_ && ambient_grid_->total_bytes() >= limit) return false;
    return !dvr_shadows_.built() || std::uint64_t(d.x) * std::uint64_t(d.y) * std::uint64_t(d.z) * 4 < limit;
  }

  SceneResources resources_;
  MomentPyramid pyramid_;
  std::optional<IsoOccupancy> occupancy_;
  LightVisibilityCaches dvr_shadows_;  // mode dvr, soft shadows: one grid per light
  std::optional<Volume> ambient_grid_;  // mode dvr, dvr_ao=grid
  PlaneCaches plane_shadows_;           // soft shadows on the planes
  std::vector<float> plane_inputs_;     // what their marches read, besides the placements
  std::uint64_t plane_version_ = 0;
  std::uint64_t plane_builds_ = 0;
  std::uint64_t pyramid_builds_ = 0;
  vec2 ambient_key_{0.0f};              // ao_combine and ao_offset it was built with
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
          ParameterSpec::choice("dvr_ao", "grid", {"grid", "sample"},
                                "mode dvr: AO evaluated once per voxel into a grid read trilinearly (grid), or per "
                                "DVR sample as the paper does (sample)"),
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

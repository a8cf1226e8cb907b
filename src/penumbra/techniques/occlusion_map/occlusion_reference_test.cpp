// occlusion-map against brute force (issue 17): soft shadows against a cone
// of iso-test rays toward a disk light (the thin-plate umbra, the penumbra
// width for two light sizes), and ambient occlusion against cosine-weighted
// iso-test rays on small volumes (procedural, a downsampled engine CT, the
// nucleon simulation, a downsampled MRI), as correlation and mean absolute
// error over the pixels of a small image. The DISABLED_ sweep prints the
// table behind the defaults (docs/PERFORMANCE.md, issue 17 section).
#include "penumbra/base/rng.h"
#include "penumbra/io/io_test_support.h"
#include "penumbra/io/volume_reader.h"
#include "penumbra/render/scene_resources.h"
#include "penumbra/techniques/occlusion_map/iso_occupancy.h"
#include "penumbra/techniques/occlusion_map/isosurface_ray.h"
#include "penumbra/techniques/occlusion_map/moment_pyramid.h"
#include "penumbra/techniques/occlusion_map/occlusion_queries.h"
#include "test_scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <optional>
#include <vector>

namespace penumbra {
namespace {

using testing::procedural_scene;
using testing::render_with;

// A float volume of dims voxels, spacing 1, centred, from f(world position).
std::shared_ptr<Volume> field(ivec3 dims, const std::function<float(vec3)>& f) {
  auto volume = std::make_shared<Volume>(dims, VoxelType::Float32);
  float* v = volume->frame_as<float>(0);
  const vec3 c = 0.5f * vec3(dims - 1);
  for (int z = 0; z < dims.z; ++z)
    for (int y = 0; y < dims.y; ++y)
      for (int x = 0; x < dims.x; ++x) *v++ = f(vec3(x, y, z) - c);
  return volume;
}

using testing::antialiased_solid;

// The first iso crossing of every pixel's ray of an image_size^2 view through
// `eye` (an IsoOccupancy view `iso_view` of the same volume finds it), with
// the viewer-facing unit normal of the central-difference gradient:
// f(x, y, p, n, sampler) for each pixel that hits a surface with a gradient.
template <class F>
void for_each_surface_pixel(const RenderView& iso_view, const RenderView& eye, float iso, int image_size, F&& f) {
  with_sampler(iso_view.volume, [&](const auto& sampler) {
    for (int y = 0; y < image_size; ++y) {
      for (int x = 0; x < image_size; ++x) {
        const Ray ray = eye.camera.pixel_ray(float(x) + 0.5f, float(y) + 0.5f, image_size, image_size);
        std::uint64_t samples = 0;
        const float t = first_iso_crossing(iso_view, sampler, ray, volume_interval(iso_view, ray, 0.0f, kInfinity),
                                           iso, samples);
        if (!(t < kInfinity)) continue;
        const vec3 p = ray.at(t);
        const vec3 g = sampler.gradient(iso_view.volume.index_from_world(p)) / iso_view.volume.spacing;
        if (!(glm::length(g) > 0.0f)) continue;
        vec3 n = -glm::normalize(g);
        if (glm::dot(n, ray.direction) > 0.0f) n = -n;
        f(x, y, p, n, sampler);
      }
    }
    return 0;
  });
}

// Pearson correlation and mean absolute error of two series.
struct Agreement {
  double correlation = 0.0, mae = 0.0, mean_map = 0.0, mean_ref = 0.0;
  int pixels = 0;
};
Agreement agreement(const std::vector<double>& map, const std::vector<double>& ref) {
  Agreement c;
  c.pixels = int(map.size());
  if (c.pixels < 2) return c;
  double smm = 0, srr = 0, smr = 0;
  for (std::size_t i = 0; i < map.size(); ++i) {
    c.mean_map += map[i];
    c.mean_ref += ref[i];
    smm += map[i] * map[i];
    srr += ref[i] * ref[i];
    smr += map[i] * ref[i];
    c.mae += std::abs(map[i] - ref[i]);
  }
  const double n = double(map.size());
  c.mean_map /= n;
  c.mean_ref /= n;
  c.mae /= n;
  const double cov = smr / n - c.mean_map * c.mean_ref;
  const double vm = smm / n - c.mean_map * c.mean_map, vr = srr / n - c.mean_ref * c.mean_ref;
  c.correlation = vm > 0.0 && vr > 0.0 ? cov / std::sqrt(vm * vr) : 0.0;
  return c;
}

// Brute-force visibility of a uniform disk light of angular radius theta
// (direction `to_light`) from p: `rays` rays on concentric strata of the cone,
// each an iso-test ray (the hard-shadow test) from p + n / 2.
struct ConeReference {
  RenderView view;  // an IsoOccupancy view of the volume
  float iso = 0.5f;
  float visibility(vec3 p, vec3 n, vec3 to_light, float theta_deg, int rings = 12) const {
    const vec3 a = glm::normalize(glm::cross(to_light, std::abs(to_light.x) < 0.9f ? vec3(1, 0, 0) : vec3(0, 1, 0)));
    const vec3 b = glm::cross(to_light, a);
    const float spread = std::tan(glm::radians(theta_deg));
    int total = 0, lit = 0;
    with_sampler(view.volume, [&](const auto& sampler) {
      for (int ring = 0; ring < rings; ++ring) {
        // Equal-area rings of the light's disk, 6 (2 ring + 1) points each.
        const float r = spread * std::sqrt((float(ring) + 0.5f) / float(rings));
        const int count = 6 * (2 * ring + 1);
        for (int k = 0; k < count; ++k) {
          const float phi = 6.2831853f * (float(k) + 0.5f * float(ring % 2)) / float(count);
          const vec3 d = glm::normalize(to_light + r * (std::cos(phi) * a + std::sin(phi) * b));
          ++total;
          lit += iso_blocks(view, sampler, Ray{p + 0.5f * n, d}, kInfinity, iso) ? 0 : 1;
        }
      }
      return 0;
    });
    return float(lit) / float(total);
  }
};

struct ShadowCase {
  std::shared_ptr<Volume> volume;
  SceneResources resources;
  std::optional<IsoOccupancy> occupancy;
  ConeReference reference;
  MomentPyramid pyramid;
  ShadowCase(std::shared_ptr<Volume> v, MomentPyramidSettings settings, float iso = 0.5f) : volume(std::move(v)) {
    Scene scene = procedural_scene("spheres", volume->dims(), 8);
    scene.set_volume(volume);
    resources.update(scene);
    occupancy.emplace(resources.macrocells(), iso);
    reference.view = occupancy->apply(resources.view(scene));
    reference.iso = iso;
    pyramid = MomentPyramid(volume->view(), vec2(0.0f, 1.0f), settings);
  }
  float map(vec3 p, vec3 n, vec3 to_light, float theta_deg) const {
    if (pyramid.moments() == 4) return query<4>(p, n, to_light, theta_deg);
    return query<2>(p, n, to_light, theta_deg);
  }
  template <int K> float query(vec3 p, vec3 n, vec3 to_light, float theta_deg) const {
    OcclusionQueries<K> q;
    q.pyramid = pyramid.view<K>();
    q.box = volume->world_box();
    // The receivers stand in empty space: nothing of their own to take out (-1).
    return q.soft_shadow(p, n, to_light, kInfinity, std::tan(glm::radians(theta_deg)), reference.iso, -1.0f);
  }
};

// A one-voxel opaque plate (v = 1 on z = 8, 0.5 at z = 8 +- 0.5) over
// receivers 20 voxels below, lit from straight above by a 3-degree light: its
// umbra lets at most 10 % through, with the default map and at full
// resolution (issue 17 measured 64 % and 59 % with the old march).
TEST(OcclusionMapReference, OneVoxelPlateCastsAnUmbra) {
  const auto plate = field(ivec3(40), [](vec3 p) { return antialiased_solid(std::abs(p.z - 8.0f) - 0.5f); });
  for (const MomentPyramidSettings& settings : {MomentPyramidSettings{}, MomentPyramidSettings{2, 1.0f, 5}}) {
    const ShadowCase c(plate, settings);
    float worst = 0.0f;
    for (const vec2& xy : {vec2(0.0f), vec2(3.3f, -2.1f), vec2(-5.5f, 4.7f)}) {
      const vec3 p(xy, -12.0f);
      const float map = c.map(p, vec3(0, 0, 1), vec3(0, 0, 1), 3.0f);
      const float ref = c.reference.visibility(p, vec3(0, 0, 1), vec3(0, 0, 1), 3.0f);
      EXPECT_EQ(ref, 0.0f);
      worst = std::max(worst, map);
    }
    std::printf("[occlusion-map reference] 1-voxel plate, resolution %.2f: most light through the umbra %.4f\n",
                settings.resolution, worst);
    EXPECT_LE(worst, 0.10f) << settings.resolution;
  }
}

// The penumbra of a half-plane plate (x < 0, 2 voxels thick) on receivers 28
// voxels below, for disk lights of 8 and 16 degrees (cone radii 3.9 and 8.0
// voxels at the plate, both at least level 0's 1.5 sigma0 = 3 voxels): its
// width (from 10 % to 90 % lit, along x) against the brute-force cone's, and
// its growth with the light's size. Measured: widths 5.9 and 12.5 voxels
// against 6.1 and 12.4, ratio 2.12 against 2.02 (before the maxima: 5.1 and
// 12.6, ratio 2.46); the map's shadow reaches 2.4-4.7 voxels further out
// (the two-valued estimate still takes a half-covered region for more than
// half), so the profile's MAE is 0.08-0.15.
struct Profile {
  double width = 0.0, mae = 0.0, centre_shift = 0.0;
};
double crossing(const std::vector<float>& v, const std::vector<float>& x, float level) {
  for (std::size_t i = 1; i < v.size(); ++i) {
    if ((v[i - 1] < level) != (v[i] < level)) {
      return x[i - 1] + (x[i] - x[i - 1]) * (level - v[i - 1]) / (v[i] - v[i - 1]);
    }
  }
  return v.front() < level ? x.back() : x.front();
}

TEST(OcclusionMapReference, PenumbraWidthFollowsTheLightSize) {
  const auto edge = field(ivec3(64), [](vec3 p) {
    return antialiased_solid(glm::max(std::abs(p.z - 14.0f) - 1.0f, p.x));
  });
  const ShadowCase c(edge, MomentPyramidSettings{});
  std::vector<float> xs;
  for (float x = -16.0f; x <= 16.0f; x += 1.0f) xs.push_back(x);
  Profile got[2], want[2];
  const float sizes[2] = {8.0f, 16.0f};
  for (int s = 0; s < 2; ++s) {
    std::vector<float> map, ref;
    for (const float x : xs) {
      const vec3 p(x, 0.5f, -14.0f);
      map.push_back(c.map(p, vec3(0, 0, 1), vec3(0, 0, 1), sizes[s]));
      ref.push_back(c.reference.visibility(p, vec3(0, 0, 1), vec3(0, 0, 1), sizes[s]));
      got[s].mae += std::abs(map.back() - ref.back()) / double(xs.size());
    }
    got[s].width = crossing(map, xs, 0.9f) - crossing(map, xs, 0.1f);
    want[s].width = crossing(ref, xs, 0.9f) - crossing(ref, xs, 0.1f);
    got[s].centre_shift = crossing(map, xs, 0.5f) - crossing(ref, xs, 0.5f);
    std::printf("[occlusion-map reference] penumbra, %.0f-degree light: width %.2f voxels (cone reference %.2f), "
                "50 %% point off by %.2f, profile MAE %.4f\n",
                sizes[s], got[s].width, want[s].width, got[s].centre_shift, got[s].mae);
  }
  for (int s = 0; s < 2; ++s) {
    EXPECT_GT(got[s].width, 0.7 * want[s].width) << sizes[s];
    EXPECT_LT(got[s].width, 1.3 * want[s].width) << sizes[s];
    EXPECT_LT(std::abs(got[s].centre_shift), 5.0) << sizes[s];
    EXPECT_LT(got[s].mae, 0.16) << sizes[s];
  }
  const double ratio = got[1].width / got[0].width, ref_ratio = want[1].width / want[0].width;
  std::printf("[occlusion-map reference] penumbra width 16 / 8 degrees: %.2f (cone reference %.2f)\n", ratio,
              ref_ratio);
  // 1.05 with the exponent over level-0 slabs; over the level's own sigma
  // (before the maxima) it was 1.22: the wider cone's plate let more through.
  EXPECT_GT(ratio, 0.9 * ref_ratio);
  EXPECT_LT(ratio, 1.15 * ref_ratio);
}

// Every occluder above the iso-value shadows, also one less dense than the
// receiving surface (issue 17: the old query, the value under the receiver,
// let it through). A dense slab (v = 1, top at z = -12) under a plate of
// v = 0.6 over x < 0 (z in [4, 7]), iso 0.3, lit from straight above by a
// 3-degree light, seen from the side under the plate: the ratio of the
// soft-shadowed image to the unshadowed one (ambient 0, no AO) is the
// visibility, per pixel; the slab's top is dark under the plate and lit
// beyond it. (Measured: mean 0.00 under the plate, 1.00 beyond.)
TEST(OcclusionMapReference, LessDenseOccludersShadowDenseReceivers) {
  const auto volume = field(ivec3(40), [](vec3 p) {
    const float slab = antialiased_solid(std::abs(p.z + 15.0f) - 3.0f);
    const float plate = 0.6f * antialiased_solid(glm::max(std::abs(p.z - 5.5f) - 1.5f, p.x));
    return glm::max(slab, plate);
  });
  Scene scene = procedural_scene("spheres", ivec3(40), 48);
  scene.set_volume(volume);
  Light light;
  light.direction = vec3(0.0f, 0.0f, -1.0f);
  scene.set_lights({light});
  Material m;
  m.ambient = 0.0f;
  scene.set_material(m);
  scene.set_camera(Camera::framing(volume->world_box(), vec3(0.0f, -1.0f, 0.8f)));
  const ParameterSettings common = {{"iso_value", 0.3}, {"ambient_occlusion", false}, {"light_size_deg", 3.0}};
  ParameterSettings soft = common, none = common;
  soft["shadows"] = std::string("soft");
  none["shadows"] = std::string("none");
  const Image shadowed = render_with(scene, "occlusion-map", soft);
  const Image open = render_with(scene, "occlusion-map", none);
  testing::save_test_image(shadowed, "occlusion-map-less-dense-occluder.png");

  SceneResources resources;
  resources.update(scene);
  const IsoOccupancy occupancy(resources.macrocells(), 0.3f);
  const RenderView view = occupancy.apply(resources.view(scene));
  double under = 0.0, beyond = 0.0;
  int n_under = 0, n_beyond = 0;
  for_each_surface_pixel(view, view, 0.3f, 48, [&](int x, int y, vec3 p, vec3, const auto&) {
    if (!(open.at(x, y).g > 0.05f)) return;
    if (std::abs(p.z + 12.0f) > 0.5f || std::abs(p.x) > 18.0f || std::abs(p.x) < 8.0f) return;
    const double ratio = double(shadowed.at(x, y).g / open.at(x, y).g);
    (p.x < 0.0f ? under : beyond) += ratio;
    ++(p.x < 0.0f ? n_under : n_beyond);
  });
  ASSERT_GT(n_under, 10);
  ASSERT_GT(n_beyond, 10);
  std::printf("[occlusion-map reference] dense slab under a v = 0.6 plate (iso 0.3): visibility %.3f under it "
              "(%d px), %.3f beyond (%d px)\n", under / n_under, n_under, beyond / n_beyond, n_beyond);
  EXPECT_LT(under / n_under, 0.1);
  EXPECT_GT(beyond / n_beyond, 0.9);
}

// ---- ambient occlusion -------------------------------------------------------

// A float volume in [0, 1] from a shared data file, box-filtered by `factor`
// per axis and normalised to its value range; nullptr when the data folder is
// absent.
std::shared_ptr<Volume> shared_volume(const std::string& file, int factor) {
  if (!std::filesystem::is_directory(test::shared_data_dir())) return nullptr;
  const auto full = read_volume(test::shared_data_dir() / file);
  const ValueRange r = full->value_range();
  const ivec3 dims = full->dims() / factor;
  auto volume = std::make_shared<Volume>(dims, VoxelType::Float32);
  float* out = volume->frame_as<float>(0);
  const float scale = 1.0f / (float(factor * factor * factor) * (r.max - r.min));
  for (int z = 0; z < dims.z; ++z)
    for (int y = 0; y < dims.y; ++y)
      for (int x = 0; x < dims.x; ++x) {
        float sum = 0.0f;
        for (int k = 0; k < factor; ++k)
          for (int j = 0; j < factor; ++j)
            for (int i = 0; i < factor; ++i) sum += full->voxel(0, ivec3(x, y, z) * factor + ivec3(i, j, k)) - r.min;
        *out++ = sum * scale;
      }
  return volume;
}

// Ambient occlusion of every surface pixel of a small image: the technique's
// (the ratio of an ambient-only image with AO to one without) against
// `rays` cosine-weighted iso-test rays (the hard-shadow test) from the
// same hit point, to the volume's boundary.
Agreement compare_ao(const std::shared_ptr<Volume>& volume, float iso, vec3 view_dir,
                        const ParameterSettings& extra, int image_size = 40, int rays = 64) {
  Scene scene = procedural_scene("spheres", volume->dims(), image_size);
  scene.set_volume(volume);
  Material m;
  m.ambient = 1.0f;
  scene.set_material(m);
  scene.set_camera(Camera::framing(volume->world_box(), view_dir));
  ParameterSettings on = {{"iso_value", double(iso)}, {"shadows", std::string("none")}};
  for (const auto& [name, value] : extra) on[name] = value;
  ParameterSettings off = on;
  off["ambient_occlusion"] = false;
  const Image with = render_with(scene, "occlusion-map", on);
  const Image without = render_with(scene, "occlusion-map", off);

  SceneResources resources;
  resources.update(scene);
  const IsoOccupancy occupancy(resources.macrocells(), iso);
  const RenderView view = occupancy.apply(resources.view(scene));
  std::vector<double> map, ref;
  const int strata = int(std::lround(std::sqrt(double(rays))));
  Pcg32 rng(3);
  for_each_surface_pixel(view, view, iso, image_size, [&](int x, int y, vec3 p, vec3 n, const auto& sampler) {
    if (with.at(x, y).a != 1.0f || !(without.at(x, y).g > 1e-3f)) return;
    const vec3 a = glm::normalize(glm::cross(n, std::abs(n.x) < 0.9f ? vec3(1, 0, 0) : vec3(0, 1, 0)));
    const vec3 b = glm::cross(n, a);
    int open = 0;
    for (int i = 0; i < strata; ++i) {
      for (int j = 0; j < strata; ++j) {
        const float u1 = (float(i) + rng.next_float()) / float(strata);
        const float u2 = (float(j) + rng.next_float()) / float(strata);
        const float r = std::sqrt(u1), phi = 6.2831853f * u2;
        const vec3 d = r * std::cos(phi) * a + r * std::sin(phi) * b + std::sqrt(1.0f - u1) * n;
        open += iso_blocks(view, sampler, Ray{p + n * view.volume.min_spacing(), d}, kInfinity, iso) ? 0 : 1;
      }
    }
    ref.push_back(double(open) / double(strata * strata));
    map.push_back(double(with.at(x, y).g / without.at(x, y).g));
  });
  return agreement(map, ref);
}

void report(const char* name, const std::string& settings, const Agreement& c) {
  std::printf("[occlusion-map ao reference] %-22s %-28s %4d px: correlation %.3f, MAE %.3f (mean %.3f vs %.3f)\n",
              name, settings.c_str(), c.pixels, c.correlation, c.mae, c.mean_map, c.mean_ref);
}

struct AoDataSet {
  const char* name;
  std::shared_ptr<Volume> volume;
  float iso;
  vec3 view_dir;
};

// A shared data file downsampled by `factor`, seen from the default
// direction, when the data folder is there.
void add_shared_volume(std::vector<AoDataSet>& sets, const char* name, const char* file, int factor, float iso) {
  if (auto v = shared_volume(file, factor)) sets.push_back({name, v, iso, vec3(0.6f, -1.0f, 0.45f)});
}

// The data sets: two procedural fields with a known shape (balls over a slab,
// the `spheres` linear-profile field: not two-valued), the engine CT
// downsampled 4x (two materials), the head CT downsampled 4x (bone at iso
// 0.47 of -1000..2000 HU in soft tissue), the nucleon simulation (a smooth density,
// 41^3, whose iso 0.1 surface is convex: the reference is 1 everywhere, so
// only its error counts) and the small MRI downsampled 2x (soft tissue at
// many values).
std::vector<AoDataSet> ao_data_sets() {
  std::vector<AoDataSet> sets;
  sets.push_back({"balls-over-slab", field(ivec3(48), [](vec3 p) {
                    return glm::max(glm::max(antialiased_solid(glm::length(p - vec3(-6.0f, 0.0f, 2.0f)) - 9.0f),
                                             antialiased_solid(glm::length(p - vec3(11.0f, 3.0f, -4.0f)) - 5.0f)),
                                    antialiased_solid(std::abs(p.z + 14.0f) - 2.0f));
                  }), 0.5f, vec3(0.4f, -1.0f, 0.7f)});
  sets.push_back({"spheres-field", make_procedural_volume("spheres", ivec3(48)), 0.3f, vec3(0.6f, -1.0f, 0.45f)});
  add_shared_volume(sets, "engine-ct/4", "engine_256x256x128_uint8.nhdr", 4, 0.5f);
  add_shared_volume(sets, "head-ct/4", "ct_head_cranium_256x256x108_int16.nhdr", 4, 0.47f);
  add_shared_volume(sets, "nucleon", "nucleon_41x41x41_uint8.nhdr", 1, 0.1f);
  add_shared_volume(sets, "mri-brainsmall/2", "mri_brainsmall_128x128x84_uint8.nhdr", 2, 0.3f);
  return sets;
}

// The defaults (moments 2, ao_combine product, ao_offset 2, chosen by the
// sweep below) against brute force, with bounds from the measured values
// (correlation / MAE: balls 0.77 / 0.062, spheres field 0.94 / 0.056, engine
// 0.93 / 0.086, head 0.80 / 0.103, MRI 0.94 / 0.096; the paper's max of the
// levels: 0.75 / 0.085, 0.87 / 0.034, 0.90 / 0.121, 0.72 / 0.074, 0.90 /
// 0.108). On the engine CT and the MRI the product also beats the max's MAE;
// on the head, the spheres field and the nucleon it is darker than both.
TEST(OcclusionMapReference, AmbientOcclusionTracksBruteForceRays) {
  struct Bound {
    const char* name;
    double correlation, mae;
  };
  const Bound bounds[] = {{"balls-over-slab", 0.72, 0.09},
                          {"spheres-field", 0.88, 0.085},
                          {"engine-ct/4", 0.88, 0.13},
                          {"head-ct/4", 0.75, 0.14},
                          {"nucleon", -1.0, 0.2},
                          {"mri-brainsmall/2", 0.88, 0.14}};
  int checked = 0;
  for (const AoDataSet& set : ao_data_sets()) {
    const Agreement c = compare_ao(set.volume, set.iso, set.view_dir, {});
    report(set.name, "defaults", c);
    ASSERT_GT(c.pixels, 40) << set.name;
    for (const Bound& b : bounds) {
      if (std::string(b.name) != set.name) continue;
      ++checked;
      EXPECT_GT(c.correlation, b.correlation) << set.name;
      EXPECT_LT(c.mae, b.mae) << set.name;
    }
    if (std::string(set.name) == "engine-ct/4" || std::string(set.name) == "mri-brainsmall/2") {
      const Agreement paper = compare_ao(set.volume, set.iso, set.view_dir, {{"ao_combine", std::string("max")}});
      report(set.name, "ao_combine max", paper);
      EXPECT_LT(c.mae, paper.mae) << set.name;
    }
  }
  EXPECT_GE(checked, 2);
}

// Soft shadows on the AO data sets and three at twice their resolution
// against a brute-force cone (3 degrees, 12 rings = 432 rays) per surface
// pixel, light from the upper front: the correlation and MAE of the
// visibility, its mean against the cone's, and the reference's umbra pixels
// (visibility < 0.1) that the map leaves more than half lit.
struct ShadowAgreement {
  Agreement agreement;
  int umbra = 0, leaking = 0;
};

ShadowAgreement compare_soft_shadows(const AoDataSet& set) {
  const ShadowCase c(set.volume, MomentPyramidSettings{}, set.iso);
  Scene scene = procedural_scene("spheres", set.volume->dims(), 40);
  scene.set_volume(set.volume);
  scene.set_camera(Camera::framing(set.volume->world_box(), set.view_dir));
  const RenderView& view = c.reference.view;
  SceneResources resources;
  resources.update(scene);
  const RenderView eye = resources.view(scene);
  const vec3 to_light = glm::normalize(vec3(-0.5f, -0.4f, 1.0f));
  std::vector<double> map, ref;
  ShadowAgreement out;
  for_each_surface_pixel(view, eye, set.iso, 40, [&](int, int, vec3 p, vec3 n, const auto& sampler) {
    if (glm::dot(n, to_light) <= 0.05f) return;  // turned away from the light
    const float under = sampler(view.volume.index_from_world(p - 0.5f * n));
    OcclusionQueries<2> q;
    q.pyramid = c.pyramid.view<2>();
    q.box = set.volume->world_box();
    const float m = q.soft_shadow(p, n, to_light, kInfinity, std::tan(glm::radians(3.0f)), set.iso,
                                  glm::max(set.iso, under));
    const float r = c.reference.visibility(p, n, to_light, 3.0f);
    map.push_back(m);
    ref.push_back(r);
    if (r < 0.1f) {
      ++out.umbra;
      out.leaking += m > 0.5f ? 1 : 0;
    }
  });
  out.agreement = agreement(map, ref);
  const Agreement& a = out.agreement;
  std::printf("[occlusion-map shadow reference] %-18s %4d px: correlation %.3f, MAE %.3f, mean %.3f vs %.3f, "
              "umbra px more than half lit %d of %d\n",
              set.name, a.pixels, a.correlation, a.mae, a.mean_map, a.mean_ref, out.leaking, out.umbra);
  return out;
}

std::vector<AoDataSet> shadow_data_sets() {
  std::vector<AoDataSet> sets = ao_data_sets();
  add_shared_volume(sets, "head-ct/2", "ct_head_cranium_256x256x108_int16.nhdr", 2, 0.47f);
  add_shared_volume(sets, "engine-ct/2", "engine_256x256x128_uint8.nhdr", 2, 0.5f);
  add_shared_volume(sets, "mri-brainsmall", "mri_brainsmall_128x128x84_uint8.nhdr", 1, 0.3f);
  return sets;
}

// Bounds at about 1.2x the measured MAE (docs/PERFORMANCE.md, issue 17
// section, "after (maxima)"), each below the Chebyshev march's error before
// the maxima; the mean visibility below the cone's by at most about 1.2x the
// measured gap (0.001 nucleon to 0.17 head CT /4: what is left of the
// defect, lit surfaces too dark), and at most a twelfth of the data sets'
// umbra pixels more than half lit (15 of 233 measured; 6 with the Chebyshev
// march before the maxima).
TEST(OcclusionMapReference, SoftShadowsTrackABruteForceConeOnDataSets) {
  struct Bound {
    const char* name;
    double mae, darker;
  };
  const Bound bounds[] = {{"balls-over-slab", 0.12, 0.09},  {"spheres-field", 0.085, 0.08},
                          {"engine-ct/4", 0.082, 0.04},     {"head-ct/4", 0.235, 0.2},
                          {"nucleon", 0.01, 0.01},          {"mri-brainsmall/2", 0.235, 0.1},
                          {"head-ct/2", 0.18, 0.18},        {"engine-ct/2", 0.08, 0.06},
                          {"mri-brainsmall", 0.2, 0.16}};
  int checked = 0, umbra = 0, leaking = 0;
  for (const AoDataSet& set : shadow_data_sets()) {
    const ShadowAgreement s = compare_soft_shadows(set);
    umbra += s.umbra;
    leaking += s.leaking;
    for (const Bound& b : bounds) {
      if (std::string(b.name) != set.name) continue;
      ++checked;
      EXPECT_LT(s.agreement.mae, b.mae) << set.name;
      EXPECT_GT(s.agreement.mean_map, s.agreement.mean_ref - b.darker) << set.name;
    }
  }
  EXPECT_GE(checked, 2);
  std::printf("[occlusion-map shadow reference] umbra pixels more than half lit: %d of %d\n", leaking, umbra);
  EXPECT_LE(leaking, umbra / 12 + 1);
}

// The measurement behind the AO defaults: every data set, for both moment
// counts, the three ways of combining the four levels and three offsets.
TEST(OcclusionMapReference, DISABLED_AmbientOcclusionSweep) {
  for (const AoDataSet& set : ao_data_sets()) {
    for (const double moments : {2.0, 4.0}) {
      for (const char* combine : {"max", "mean", "product"}) {
        for (const double offset : {1.0, 2.0, 3.0}) {
          const ParameterSettings p = {{"moments", moments}, {"ao_combine", std::string(combine)},
                                       {"ao_offset", offset}};
          char label[64];
          std::snprintf(label, sizeof label, "moments %d %s offset %.0f", int(moments), combine, offset);
          report(set.name, label, compare_ao(set.volume, set.iso, set.view_dir, p));
        }
      }
    }
  }
}

}  // namespace
}  // namespace penumbra

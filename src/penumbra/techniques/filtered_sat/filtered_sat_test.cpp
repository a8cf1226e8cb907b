// filtered-sat as a technique: convergence to shadow-rays, orthodirectional
// table sharing, rebuild logic, time series, the cache, bad parameters.
#include "penumbra/analysis/image_metrics.h"
#include "penumbra/base/error.h"
#include "penumbra/base/memory_budget.h"
#include "penumbra/render/scene_resources.h"
#include "penumbra/techniques/filtered_sat/light_tables.h"
#include "penumbra/techniques/filtered_sat/shadow_filter.h"
#include "penumbra/techniques/registry.h"
#include "penumbra/techniques/sat_common/visibility_cache.h"
#include "test_scene.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdio>

namespace penumbra {
namespace {

using testing::procedural_scene;
using testing::render_with;

Scene lit_spheres(vec3 direction = vec3(0.4f, 0.6f, -1.0f)) {
  Scene scene = procedural_scene("spheres", ivec3(40), 40);
  TransferFunction tf({{0.0f, vec3(1.0f, 0.7f, 0.4f), 0.0f},
                       {0.1f, vec3(1.0f, 0.7f, 0.4f), 0.0f},
                       {0.4f, vec3(1.0f, 0.7f, 0.4f), 0.25f},
                       {1.0f, vec3(0.9f, 0.9f, 1.0f), 0.6f}});
  tf.set_range(vec2(0.0f, 1.0f));
  scene.set_transfer_function(tf);
  Light light;
  light.direction = glm::normalize(direction);
  scene.set_lights({light});
  Material m;
  m.ambient = 0.0f;
  scene.set_material(m);
  return scene;
}

// lit_spheres with a second light, a point light at the upper left.
Scene lit_spheres_and_a_point_light() {
  Scene scene = lit_spheres();
  Light point;
  point.type = LightType::Point;
  point.position = vec3(-30.0f, -40.0f, 45.0f);
  point.intensity = 4500.0f;
  scene.set_lights({scene.lights()[0], point});
  return scene;
}

// As the patch shrinks to a voxel, the mean optical depth over it becomes the
// optical depth of the one shadow ray: the image error against shadow-rays
// falls monotonically and ends at the tables' discretisation (cells of half
// a voxel here, so that it is small).
TEST(FilteredSat, ConvergesToShadowRaysAsTheFilterShrinks) {
  for (const LightType type : {LightType::Directional, LightType::Point}) {
    Scene scene = lit_spheres();
    if (type == LightType::Point) {
      Light point;
      point.type = LightType::Point;
      point.position = vec3(-30.0f, -40.0f, 45.0f);
      point.intensity = 4500.0f;
      scene.set_lights({point});
    }
    const Image reference = render_with(scene, "shadow-rays");
    double previous = 1e30;
    for (const double width : {12.0, 6.0, 3.0, 1.0}) {
      const Image image = render_with(
          scene, "filtered-sat", {{"filter_voxels", width}, {"shadow_cache", false}, {"sat_resolution", 2.0}});
      const double error = rmse(image, reference);
      std::printf("%s filter %.0f: rmse %.5f\n", type == LightType::Point ? "point" : "directional", width, error);
      EXPECT_LT(error, previous) << "filter " << width;
      previous = error;
    }
    // The shadows are up to ~0.5 deep in this scene; 1% of that remains.
    EXPECT_LT(previous, 0.005);
  }
}

// Three orthogonal lights read one CSAT: the tables take as much memory as
// for one light, and (lighting being additive with ambient 0) the image is
// the sum of the three single-light images. With the lights along the world
// axes, each single light's own table has the same cells, so the sums agree
// to float rounding; rotated, each single light's table is fitted to its own
// frame and the images differ by the tables' discretisation (observed rmse
// 2e-4).
TEST(FilteredSat, ThreeOrthodirectionalLightsShareOneTable) {
  const mat3 rotations[] = {mat3(1.0f), mat3(glm::rotate(glm::mat4(1.0f), 0.6f, glm::normalize(vec3(1, 2, 3))))};
  for (int r = 0; r < 2; ++r) {
    Scene scene = lit_spheres();
    std::vector<Light> lights(3);
    const vec3 axes[3] = {vec3(0, 0, -1), vec3(1, 0, 0), vec3(0, -1, 0)};
    for (int i = 0; i < 3; ++i) {
      lights[std::size_t(i)].direction = rotations[r] * axes[i];
      lights[std::size_t(i)].intensity = 0.5f;
    }
    const ParameterSettings params = {{"filter_voxels", 4.0}, {"shadow_cache", false}};
    const TechniqueInfo& info = find_technique("filtered-sat");
    ParameterValues values(info.parameters);
    values.apply(params, true);

    scene.set_lights({lights[0]});
    auto single = info.create();
    single->prepare(scene, values);
    const std::uint64_t one_table = single->aux_bytes();
    Image sum(40, 40);
    for (const Light& l : lights) {
      scene.set_lights({l});
      const Image part = render_with(scene, "filtered-sat", params);
      for (std::size_t p = 0; p < sum.pixel_count(); ++p) sum.data()[p] += vec4(vec3(part.data()[p]), 0.0f);
    }
    scene.set_lights(lights);
    auto three = info.create();
    three->prepare(scene, values);
    Image all;
    three->render(scene, all);
    const double error = rmse(all, sum);
    std::printf("rotation %d: tables %llu vs %llu bytes, rmse %.6f\n", r, (unsigned long long)three->aux_bytes(),
                (unsigned long long)one_table, error);
    if (r == 0) {
      EXPECT_EQ(three->aux_bytes(), one_table);
      EXPECT_LT(error, 1e-5);
    } else {
      // A rotated frame: one table for the three, fitted to their common
      // frame (a larger box around the volume than a single light's frame,
      // which follows the world axes where it can).
      SceneResources resources;
      resources.update(scene);
      LightTables tables;
      tables.build(resources.shadow_view(scene), lights, 1.0f);
      EXPECT_EQ(tables.table_count(), 1);
      EXPECT_EQ(three->aux_bytes(), tables.bytes());
      EXPECT_LT(error, 0.002);
    }
    // A non-orthogonal fourth light needs a table of its own.
    const std::uint64_t shared = three->aux_bytes();
    Light extra;
    extra.direction = glm::normalize(vec3(1.0f, 1.0f, -1.0f));
    lights.push_back(extra);
    scene.set_lights(lights);
    three->prepare(scene, values);
    EXPECT_GT(three->aux_bytes(), shared + one_table / 2);
  }
}

TEST(FilteredSat, FilterChangesNeverRebuildTheTables) {
  const TechniqueInfo& info = find_technique("filtered-sat");
  for (const bool cache : {false, true}) {
    Scene scene = lit_spheres();
    ParameterValues params(info.parameters);
    params.set("shadow_cache", cache);
    auto t = info.create();
    t->prepare(scene, params);
    const std::uint64_t built = t->rebuilds();
    EXPECT_EQ(built, cache ? 2u : 1u);  // tables (+ cache)
    Image narrow, wide;
    t->render(scene, narrow);
    params.set("filter_voxels", 12.0);
    t->prepare(scene, params);
    t->render(scene, wide);
    // Without the cache nothing is rebuilt; with it only the cache is.
    EXPECT_EQ(t->rebuilds(), built + (cache ? 1u : 0u));
    EXPECT_GT(rmse(narrow, wide), 1e-3) << "the filter must change the image";
    params.set("kernel", std::string("gaussian"));
    params.set("shadow_density_scale", 0.5);
    t->prepare(scene, params);
    EXPECT_EQ(t->rebuilds(), built + (cache ? 2u : 0u));
    // Camera and material changes rebuild nothing; a light move, an
    // extinction edit and clip planes rebuild the tables.
    Camera camera = scene.camera();
    camera.orbit(20.0f, 5.0f);
    scene.set_camera(camera);
    scene.set_material(Material{});
    t->prepare(scene, params);
    EXPECT_EQ(t->rebuilds(), built + (cache ? 2u : 0u));
    const std::uint64_t before = t->rebuilds();
    Light moved = scene.lights()[0];
    moved.direction = glm::normalize(vec3(-0.3f, 0.6f, -1.0f));
    scene.set_lights({moved});
    t->prepare(scene, params);
    EXPECT_EQ(t->rebuilds(), before + built);
    TransferFunction denser = scene.transfer_function();
    denser.set_density_scale(2.0f);
    scene.set_transfer_function(denser);
    t->prepare(scene, params);
    EXPECT_EQ(t->rebuilds(), before + 2 * built);
    scene.set_clip_planes({vec4(0.0f, 0.0f, 1.0f, 5.0f)});
    t->prepare(scene, params);
    EXPECT_EQ(t->rebuilds(), before + 3 * built);
    params.set("sat_resolution", 0.5);
    t->prepare(scene, params);
    EXPECT_EQ(t->rebuilds(), before + 4 * built);
  }
}

// Issue 22: only what a table depends on rebuilds it. A light's colour and
// intensity, a floor plane, re-setting equal lights or TF, and a render-only
// TF edit while a separate shadow TF is set rebuild nothing; moving one of
// two lights rebuilds that light's table and cache only; a shadow-TF edit
// rebuilds both lights' tables and caches.
TEST(FilteredSat, OnlyWhatATableDependsOnRebuildsIt) {
  for (const std::string technique : {"filtered-sat", "cone-shadows", "sat-ao"}) {
    Scene scene = lit_spheres_and_a_point_light();
    scene.set_shadow_transfer_function(scene.transfer_function());
    const TechniqueInfo& info = find_technique(technique);
    const ParameterValues params(info.parameters);
    auto t = info.create();
    t->prepare(scene, params);
    const bool per_light = technique != "sat-ao";
    // Tables: filtered-sat one per light here, the baselines one in all;
    // caches: one per light (sat-ao: one).
    const std::uint64_t tables = technique == "filtered-sat" ? 2u : 1u, caches = per_light ? 2u : 1u;
    EXPECT_EQ(t->rebuilds(), tables + caches) << technique;
    const std::uint64_t built = t->rebuilds();
    std::vector<Light> lights = scene.lights();
    lights[0].color = vec3(0.2f, 0.5f, 1.0f);
    lights[1].intensity = 900.0f;
    scene.set_lights(lights);
    scene.set_planes({Plane{vec3(0.0f, 0.0f, -30.0f), vec3(0.0f, 0.0f, 1.0f), vec3(0.8f)}});
    scene.set_planes({Plane{vec3(0.0f, 0.0f, -35.0f), vec3(0.0f, 0.0f, 1.0f), vec3(0.5f)}});
    TransferFunction render_only = scene.transfer_function();
    render_only.set_density_scale(0.5f);
    scene.set_transfer_function(render_only);
    scene.set_shadow_transfer_function(scene.shadow_transfer_function());
    t->prepare(scene, params);
    EXPECT_EQ(t->rebuilds(), built) << technique << ": colour, intensity, floor or render TF rebuilt something";
    lights[1].position += vec3(5.0f, 0.0f, 0.0f);
    scene.set_lights(lights);
    t->prepare(scene, params);
    EXPECT_EQ(t->rebuilds(), built + (technique == "filtered-sat" ? 2u : per_light ? 1u : 0u)) << technique;
    TransferFunction shadow = *scene.shadow_transfer_function();
    shadow.set_density_scale(2.0f);
    scene.set_shadow_transfer_function(shadow);
    const std::uint64_t moved = t->rebuilds();
    t->prepare(scene, params);
    EXPECT_EQ(t->rebuilds(), moved + tables + caches) << technique;
  }
}

// Issue 22, memory: with the cache read everywhere (cache_tolerance 1) and
// no floor, nothing reads the tables at render time, so each table lives
// only while its lights' caches are filled: what stays is one float cache
// per light, cache_resolution^3 * 4 bytes per voxel per light (0.5 bytes at
// the default 0.5), 16 MiB for a 256^3 volume with a directional and a
// point light (the target: 32 MiB). The image is that of the kept
// tables at the same settings; a light that moves gets its table rebuilt
// (and only its cache), a colour change rebuilds nothing; a floor or a
// tolerance below 1 brings the tables back.
TEST(FilteredSat, TablesAreReleasedOnceTheCachesAreFilled) {
  Scene scene = lit_spheres_and_a_point_light();
  const TechniqueInfo& info = find_technique("filtered-sat");
  ParameterValues released(info.parameters);
  released.set("cache_tolerance", 1.0);
  auto t = info.create();
  t->prepare(scene, released);
  EXPECT_EQ(t->rebuilds(), 4u);  // two tables, two caches
  const ivec3 dims = visibility_cache_dims(scene.volume().dims(), 0.5f);
  const std::uint64_t cache_bytes = std::uint64_t(dims.x) * dims.y * dims.z * sizeof(float);
  EXPECT_EQ(t->aux_bytes(), 2 * cache_bytes);
  const ivec3 data = scene.volume().dims();
  const double per_voxel_per_light = double(cache_bytes) / (double(data.x) * data.y * data.z);
  const double at_256 = 2.0 * per_voxel_per_light * 256.0 * 256.0 * 256.0 / (1024.0 * 1024.0);
  std::printf("released: %.3f bytes per voxel per light, %.1f MiB for 256^3 with two lights\n", per_voxel_per_light,
              at_256);
  EXPECT_LT(at_256, 32.0);
  Image image;
  t->render(scene, image);

  // The same image from kept tables (a tolerance just below 1 keeps them;
  // no cache cell's texels differ that much here).
  ParameterValues almost = released;
  almost.set("cache_tolerance", 0.9999);
  auto kept = info.create();
  kept->prepare(scene, almost);
  EXPECT_GT(kept->aux_bytes(), 2 * cache_bytes);
  Image kept_image;
  kept->render(scene, kept_image);
  EXPECT_LT(rmse(image, kept_image), 1e-6);
  // A floor is lit from the tables: they stay.
  Scene with_floor = scene;
  with_floor.set_planes({Plane{vec3(0.0f, 0.0f, -30.0f), vec3(0.0f, 0.0f, 1.0f), vec3(0.5f)}});
  auto floor = info.create();
  floor->prepare(with_floor, released);
  EXPECT_EQ(floor->aux_bytes(), kept->aux_bytes());

  std::vector<Light> lights = scene.lights();
  lights[0].color = vec3(0.3f, 0.6f, 1.0f);
  scene.set_lights(lights);
  t->prepare(scene, released);
  EXPECT_EQ(t->rebuilds(), 4u);
  lights[1].position += vec3(6.0f, 0.0f, 0.0f);
  scene.set_lights(lights);
  t->prepare(scene, released);
  EXPECT_EQ(t->rebuilds(), 6u);  // that light's table and cache
  EXPECT_EQ(t->aux_bytes(), 2 * cache_bytes);
  t->render(scene, image);
  EXPECT_LT(rmse(image, render_with(scene, "filtered-sat", {{"cache_tolerance", 1.0}})), 1e-6);

  // Back to the default tolerance: the tables are needed again.
  t->prepare(scene, ParameterValues(info.parameters));
  EXPECT_GT(t->aux_bytes(), 2 * cache_bytes);
  t->render(scene, image);
  EXPECT_LT(rmse(image, render_with(scene, "filtered-sat")), 1e-6);
}

// A time series re-prepares on a time-step change with no other action: the
// image follows the frame and equals a fresh technique's image of it.
TEST(FilteredSat, TimeSeriesFollowsTheTimeStep) {
  auto series = std::make_shared<Volume>(ivec3(24), VoxelType::Float32, 2);
  for (int f = 0; f < 2; ++f) {
    float* v = series->frame_as<float>(f);
    for (int z = 0; z < 24; ++z)
      for (int y = 0; y < 24; ++y)
        for (int x = 0; x < 24; ++x) {
          // A blob that moves along x from frame to frame.
          const float dx = float(x) - (f == 0 ? 8.0f : 16.0f), dy = float(y) - 12.0f, dz = float(z) - 14.0f;
          v[x + 24 * (y + 24 * z)] = std::max(0.0f, 1.0f - std::sqrt(dx * dx + dy * dy + dz * dz) / 6.0f);
        }
  }
  series->center_at_origin();
  Scene scene = lit_spheres(vec3(0.0f, 0.0f, -1.0f));
  scene.set_volume(series, 0);
  scene.set_planes({Plane{vec3(0.0f, 0.0f, -13.0f), vec3(0.0f, 0.0f, 1.0f), vec3(0.8f)}});
  scene.set_camera(Camera::framing(series->world_box(), vec3(0.3f, -1.0f, 0.6f)));
  const TechniqueInfo& info = find_technique("filtered-sat");
  const ParameterValues params(info.parameters);
  auto t = info.create();
  t->prepare(scene, params);
  Image first;
  t->render(scene, first);
  const std::uint64_t built = t->rebuilds();
  scene.set_time_step(1);
  t->prepare(scene, params);
  EXPECT_GT(t->rebuilds(), built);
  Image second;
  t->render(scene, second);
  EXPECT_GT(rmse(first, second), 0.01);
  EXPECT_LT(rmse(second, render_with(scene, "filtered-sat")), 1e-6);
}

// The cache stores the transmittance on a grid (here at the data
// resolution); interpolating it instead of looking up per sample changes the
// image by the interpolation error only.
TEST(FilteredSat, CacheMatchesPerSampleLookups) {
  Scene scene = lit_spheres();
  Light point;
  point.type = LightType::Point;
  point.position = vec3(4.0f, -3.0f, 2.0f);  // inside the volume
  point.intensity = 300.0f;
  std::vector<Light> lights = scene.lights();
  lights.push_back(point);
  scene.set_lights(lights);
  const Image direct = render_with(scene, "filtered-sat", {{"shadow_cache", false}});
  const Image cached = render_with(scene, "filtered-sat", {{"shadow_cache", true}, {"cache_resolution", 1.0}});
  for (const vec4& p : cached.pixels()) ASSERT_TRUE(std::isfinite(p.r) && std::isfinite(p.g) && std::isfinite(p.b));
  EXPECT_LT(rmse(direct, cached), 0.01);
  EXPECT_GT(rmse(direct, render_with(scene, "filtered-sat", {{"shadow_density_scale", 0.0}})), 0.02);
}

TEST(FilteredSat, ZeroDensityScaleIsUnshadowedSingleScattering) {
  const Scene scene = lit_spheres();
  EXPECT_LT(rmse(render_with(scene, "filtered-sat", {{"shadow_density_scale", 0.0}}),
                 render_with(scene, "shadow-rays", {{"shadow_density_scale", 0.0}})),
            1e-6);
}

TEST(FilteredSat, BadParametersAndBudgetsAreTypedErrors) {
  const Scene scene = lit_spheres();
  EXPECT_THROW(render_with(scene, "filtered-sat", {{"kernel", std::string("tent")}}), InvalidArgument);
  EXPECT_THROW(render_with(scene, "filtered-sat", {{"filter_voxels", 0.0}}), InvalidArgument);
  EXPECT_THROW(render_with(scene, "filtered-sat", {{"sat_resolution", 50.0}}), InvalidArgument);
  const std::uint64_t budget = memory_budget_bytes();
  set_memory_budget_bytes(64 * 1024);
  EXPECT_THROW(render_with(scene, "filtered-sat"), OutOfMemoryBudget);
  set_memory_budget_bytes(budget);
}

// The Gaussian taps: symmetric, summing to 1, and the kernel as applied
// (each tap's weight spread evenly over its sub-patch) has the variance of
// the box it stands for, w^2 / 12.
TEST(ShadowFilter, GaussianHasTheBoxVariance) {
  const float width = 9.0f;
  const ShadowFilter g = make_shadow_filter(FilterKernel::Gaussian, width, 1.0f);
  const ShadowFilter b = make_shadow_filter(FilterKernel::Box, width, 1.0f);
  EXPECT_EQ(b.taps, 1);
  EXPECT_FLOAT_EQ(b.half_width, 4.5f);
  double sum = 0.0, variance = 0.0;
  const double step = 2.0 * g.half_width / g.taps;
  for (int i = 0; i < g.taps; ++i) {
    sum += g.weights[i];
    EXPECT_NEAR(g.weights[i], g.weights[g.taps - 1 - i], 1e-6);
    const double a = -g.half_width + i * step, c = a + step;
    variance += g.weights[i] * (c * c * c - a * a * a) / (3.0 * step);
  }
  EXPECT_NEAR(sum, 1.0, 1e-6);
  EXPECT_NEAR(variance, width * width / 12.0, 1e-4 * width * width / 12.0);
  // The taps follow the Gaussian: the central ones weigh the most, the
  // outermost (2.25 to 3 sigma) about 1%.
  EXPECT_GT(g.weights[3], 0.25f);
  EXPECT_LT(g.weights[0], 0.015f);
}

}  // namespace
}  // namespace penumbra

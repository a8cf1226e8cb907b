// filtered-sat as a technique: convergence to shadow-rays, orthodirectional
// table sharing, rebuild logic, time series, the cache, bad parameters.
#include "penumbra/analysis/image_metrics.h"
#include "penumbra/base/error.h"
#include "penumbra/base/memory_budget.h"
#include "penumbra/render/scene_resources.h"
#include "penumbra/techniques/filtered_sat/filtered_sat_test_scenes.h"
#include "penumbra/techniques/filtered_sat/light_tables.h"
#include "penumbra/techniques/filtered_sat/shadow_filter.h"
#include "penumbra/techniques/registry.h"
#include "test_scene.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdio>

namespace penumbra {
namespace {

using testing::sat_spheres;
using testing::sat_spheres_and_a_point_light;
using testing::render_with;

// As the patch shrinks to a voxel, the mean optical depth over it becomes the
// optical depth of the one shadow ray: the image error against shadow-rays
// falls monotonically and ends at the tables' discretisation (cells of half
// a voxel here, so that it is small).
TEST(FilteredSat, ConvergesToShadowRaysAsTheFilterShrinks) {
  for (const LightType type : {LightType::Directional, LightType::Point}) {
    Scene scene = sat_spheres();
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
    Scene scene = sat_spheres();
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

// With the tables kept (no cache, or a cache whose rough cells read them:
// cache_refinement 0) a filter change rebuilds at most the cache; at the
// defaults the tables are released once the cache is filled, so it rebuilds
// the table with the cache.
TEST(FilteredSat, FilterChangesNeverRebuildKeptTables) {
  const TechniqueInfo& info = find_technique("filtered-sat");
  enum class Mode { NoCache, KeptTables, Defaults };
  for (const Mode mode : {Mode::NoCache, Mode::KeptTables, Mode::Defaults}) {
    const bool cache = mode != Mode::NoCache;
    Scene scene = sat_spheres();
    ParameterValues params(info.parameters);
    params.set("shadow_cache", cache);
    if (mode == Mode::KeptTables) params.set("cache_refinement", 0.0);
    auto t = info.create();
    t->prepare(scene, params);
    const std::uint64_t built = t->rebuilds();
    EXPECT_EQ(built, cache ? 2u : 1u);  // tables (+ cache)
    // What a filter change rebuilds: nothing, the cache, or table and cache.
    const std::uint64_t filter_change = mode == Mode::NoCache ? 0u : mode == Mode::KeptTables ? 1u : 2u;
    Image narrow, wide;
    t->render(scene, narrow);
    params.set("filter_voxels", 12.0);
    t->prepare(scene, params);
    t->render(scene, wide);
    EXPECT_EQ(t->rebuilds(), built + filter_change);
    EXPECT_GT(rmse(narrow, wide), 1e-3) << "the filter must change the image";
    params.set("kernel", std::string("gaussian"));
    params.set("shadow_density_scale", 0.5);
    t->prepare(scene, params);
    EXPECT_EQ(t->rebuilds(), built + 2 * filter_change);
    // Camera and material changes rebuild nothing; a light move, an
    // extinction edit and clip planes rebuild the tables.
    Camera camera = scene.camera();
    camera.orbit(20.0f, 5.0f);
    scene.set_camera(camera);
    scene.set_material(Material{});
    t->prepare(scene, params);
    EXPECT_EQ(t->rebuilds(), built + 2 * filter_change);
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
// intensity, re-setting equal lights or TF, and a render-only TF edit while
// a separate shadow TF is set rebuild nothing; moving one of two lights
// rebuilds that light's table and cache only; a shadow-TF edit rebuilds both
// lights' tables and caches. A floor move rebuilds nothing the baselines
// count; filtered-sat's floor grids need its tables, which the defaults
// release once the caches are filled: they are rebuilt, one at a time, and
// the 3D caches are not (with the tables kept, cache_refinement 0, nothing).
TEST(FilteredSat, OnlyWhatATableDependsOnRebuildsIt) {
  for (const std::string technique : {"filtered-sat", "filtered-sat kept", "cone-shadows", "sat-ao"}) {
    const bool filtered = technique.rfind("filtered-sat", 0) == 0;
    Scene scene = sat_spheres_and_a_point_light();
    scene.set_shadow_transfer_function(scene.transfer_function());
    scene.set_planes({Plane{vec3(0.0f, 0.0f, -30.0f), vec3(0.0f, 0.0f, 1.0f), vec3(0.8f)}});
    const TechniqueInfo& info = find_technique(filtered ? "filtered-sat" : technique);
    ParameterValues params(info.parameters);
    if (technique == "filtered-sat kept") params.set("cache_refinement", 0.0);
    auto t = info.create();
    t->prepare(scene, params);
    const bool per_light = technique != "sat-ao";
    // Tables: filtered-sat one per light here, the baselines one in all;
    // caches: one per light (sat-ao: one).
    const std::uint64_t tables = filtered ? 2u : 1u, caches = per_light ? 2u : 1u;
    EXPECT_EQ(t->rebuilds(), tables + caches) << technique;
    const std::uint64_t built = t->rebuilds();
    std::vector<Light> lights = scene.lights();
    lights[0].color = vec3(0.2f, 0.5f, 1.0f);
    lights[1].intensity = 900.0f;
    scene.set_lights(lights);
    TransferFunction render_only = scene.transfer_function();
    render_only.set_density_scale(0.5f);
    scene.set_transfer_function(render_only);
    scene.set_shadow_transfer_function(scene.shadow_transfer_function());
    t->prepare(scene, params);
    EXPECT_EQ(t->rebuilds(), built) << technique << ": colour, intensity or render TF rebuilt something";
    scene.set_planes({Plane{vec3(0.0f, 0.0f, -35.0f), vec3(0.0f, 0.0f, 1.0f), vec3(0.5f)}});
    t->prepare(scene, params);
    EXPECT_EQ(t->rebuilds(), built + (technique == "filtered-sat" ? tables : 0u)) << technique << ": floor move";
    Image image, fresh_image;
    t->render(scene, image);
    auto fresh = info.create();
    fresh->prepare(scene, params);
    fresh->render(scene, fresh_image);
    EXPECT_EQ(rmse(image, fresh_image), 0.0) << technique;
    const std::uint64_t floor_moved = t->rebuilds();
    lights[1].position += vec3(5.0f, 0.0f, 0.0f);
    scene.set_lights(lights);
    t->prepare(scene, params);
    EXPECT_EQ(t->rebuilds(), floor_moved + (filtered ? 2u : per_light ? 1u : 0u)) << technique;
    TransferFunction shadow = *scene.shadow_transfer_function();
    shadow.set_density_scale(2.0f);
    scene.set_shadow_transfer_function(shadow);
    const std::uint64_t moved = t->rebuilds();
    t->prepare(scene, params);
    EXPECT_EQ(t->rebuilds(), moved + tables + caches) << technique;
  }
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
  Scene scene = sat_spheres(vec3(0.0f, 0.0f, -1.0f));
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
  Scene scene = sat_spheres();
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
  const Scene scene = sat_spheres();
  EXPECT_LT(rmse(render_with(scene, "filtered-sat", {{"shadow_density_scale", 0.0}}),
                 render_with(scene, "shadow-rays", {{"shadow_density_scale", 0.0}})),
            1e-6);
}

TEST(FilteredSat, BadParametersAndBudgetsAreTypedErrors) {
  const Scene scene = sat_spheres();
  EXPECT_THROW(render_with(scene, "filtered-sat", {{"kernel", std::string("tent")}}), InvalidArgument);
  EXPECT_THROW(render_with(scene, "filtered-sat", {{"filter_voxels", 0.0}}), InvalidArgument);
  EXPECT_THROW(render_with(scene, "filtered-sat", {{"sat_resolution", 50.0}}), InvalidArgument);
  EXPECT_THROW(render_with(scene, "filtered-sat", {{"cache_refinement", 1.0}}), InvalidArgument);
  EXPECT_THROW(render_with(scene, "filtered-sat", {{"cache_refinement", 9.0}}), InvalidArgument);
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

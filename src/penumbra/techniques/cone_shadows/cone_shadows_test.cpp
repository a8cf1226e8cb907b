// cone-shadows: an analytic slab, convergence to shadow-rays for a narrow
// cone, softening with the angle, and what rebuilds when.
#include "penumbra/analysis/image_metrics.h"
#include "penumbra/base/rng.h"
#include "penumbra/techniques/cone_shadows/cone_march.h"
#include "penumbra/techniques/registry.h"
#include "penumbra/techniques/sat_common/volume_aligned_table.h"
#include "penumbra_edge.h"
#include "test_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace penumbra {
namespace {

using testing::procedural_scene;
using testing::render_with;

// A cone of angle 0 is a column of cubes one step wide: inside a homogeneous
// slab every cube is full, so the optical depth is sigma times the distance
// to the box face, at any step (the last step is cut to the face).
TEST(ConeShadows, NarrowConeThroughASlabIsAnalytic) {
  Scene scene = procedural_scene("slab", ivec3(32), 8);
  scene.set_transfer_function(testing::step_tf(0.0f, vec3(1.0f), 0.2f));
  SceneResources resources;
  resources.update(scene);
  VolumeAlignedTable table("test");
  table.update(scene, resources, 1.0);
  const float sigma = -std::log(0.8f);
  const Box3 box = scene.volume().world_box();
  for (const float step : {1.0f, 3.0f, 7.0f}) {
    const ConeMarch cone{table.view(), table.grid(), box, 0.0f, step, 1.0f};
    const vec3 p(2.0f, -3.0f, -4.25f);
    EXPECT_NEAR(cone.optical_depth(p, vec3(0.0f, 0.0f, 1.0f), kInfinity), sigma * (box.upper.z - p.z), 1e-3f);
    EXPECT_NEAR(cone.optical_depth(p, vec3(0.0f, 0.0f, 1.0f), 6.0f), sigma * 6.0f, 1e-3f) << "point light at 6";
  }
}

// Spheres with a smoothly varying extinction over a floor.
Scene spheres_over_floor(int size = 40) {
  Scene scene = procedural_scene("spheres", ivec3(size), size);
  TransferFunction tf({{0.0f, vec3(1.0f), 0.0f}, {0.1f, vec3(1.0f), 0.0f}, {1.0f, vec3(1.0f), 0.5f}});
  tf.set_range(vec2(0.0f, 1.0f));
  scene.set_transfer_function(tf);
  Light light;
  light.direction = glm::normalize(vec3(0.2f, 0.1f, -1.0f));
  scene.set_lights({light});
  Material m;
  m.ambient = 0.0f;
  scene.set_material(m);
  scene.set_planes({Plane{vec3(0.0f, 0.0f, scene.volume().world_box().lower.z), vec3(0.0f, 0.0f, 1.0f), vec3(0.8f)}});
  scene.set_camera(Camera::framing(scene.volume().world_box(), vec3(0.2f, -1.0f, 1.2f)));
  return scene;
}

// With a narrow cone and short steps the cubes shrink to the shadow ray and
// the image approaches shadow-rays (up to the table's cell-wise constant
// extinction); widening the cone moves it away (softer shadows),
// monotonically.
TEST(ConeShadows, NarrowConesApproachShadowRaysAndWideOnesSoften) {
  const Scene scene = spheres_over_floor();
  const Image reference = render_with(scene, "shadow-rays");
  double previous = 0.0;
  for (const double angle : {0.0, 3.0, 8.0, 15.0}) {
    const double error = rmse(render_with(scene, "cone-shadows", {{"cone_angle_deg", angle}, {"step_voxels", 1.0},
                                                                  {"shadow_cache", false}}),
                              reference);
    std::printf("cone %.0f deg: rmse %.5f\n", angle, error);
    if (angle == 0.0) {
      EXPECT_LT(error, 0.01);
    }
    EXPECT_GT(error, previous);
    previous = error;
  }
}

TEST(ConeShadows, LightMovesRebuildOnlyTheCaches) {
  Scene scene = spheres_over_floor(24);
  const TechniqueInfo& info = find_technique("cone-shadows");
  ParameterValues params(info.parameters);
  auto t = info.create();
  t->prepare(scene, params);
  EXPECT_EQ(t->rebuilds(), 2u);  // table and caches
  Light moved = scene.lights()[0];
  moved.direction = glm::normalize(vec3(-0.3f, 0.2f, -1.0f));
  scene.set_lights({moved});
  t->prepare(scene, params);
  EXPECT_EQ(t->rebuilds(), 3u);
  params.set("shadow_cache", false);
  scene.set_lights(scene.lights());
  t->prepare(scene, params);
  EXPECT_EQ(t->rebuilds(), 3u) << "without the cache lights are read per sample";
  TransferFunction denser = scene.transfer_function();
  denser.set_density_scale(2.0f);
  scene.set_transfer_function(denser);
  t->prepare(scene, params);
  EXPECT_EQ(t->rebuilds(), 4u);
  // The cache at the data resolution interpolates the per-sample
  // transmittance: a small difference only.
  Image cached, direct;
  t->render(scene, direct);
  params.set("shadow_cache", true);
  params.set("cache_resolution", 1.0);
  t->prepare(scene, params);
  t->render(scene, cached);
  EXPECT_LT(rmse(cached, direct), 0.01);
}

// cone_angle_deg unset follows each light's size (cone_shadows.h); set, it
// overrides it; a light's size change rebuilds its cache.
TEST(ConeShadows, ConeAngleFollowsTheLightUnlessSet) {
  Scene scene = spheres_over_floor(24);
  const Light directional = scene.lights()[0];
  const Light distant = testing::as_distant(directional, 12.0f);
  const Image overridden =
      testing::expect_knob_overrides_light(scene, "cone-shadows", {}, "cone_angle_deg", distant, 12.0, directional,
                                           5.0, 2.0);
  auto with = [&](const Light& light, double angle) {
    Scene s = scene;
    s.set_lights({light});
    return angle < 0.0 ? render_with(s, "cone-shadows") : render_with(s, "cone-shadows", {{"cone_angle_deg", angle}});
  };
  Light gaussian = distant;
  gaussian.profile = LightProfile::Gaussian;
  gaussian.angle_deg = 4.0f;
  const double equal_variance = glm::degrees(std::atan(2.0 * std::tan(glm::radians(4.0))));
  EXPECT_LT(rmse(with(gaussian, -1.0), with(gaussian, equal_variance)), 1e-6) << "a Gaussian: tan = 2 tan(sigma)";

  // One technique, the light shrinking: its cache follows.
  const TechniqueInfo& info = find_technique("cone-shadows");
  const ParameterValues params(info.parameters);
  auto technique = info.create();
  Scene s = scene;
  s.set_lights({distant});
  technique->prepare(s, params);
  Light small = distant;
  small.angle_deg = 2.0f;
  s.set_lights({small});
  technique->prepare(s, params);
  Image image;
  technique->render(s, image);
  EXPECT_LT(rmse(image, overridden), 1e-6);
}

// The sharp edge of tests/support/penumbra_edge.h under distant uniform
// lights: with the derived cone the 10-90 % penumbra scales with the light,
// tan(12) / tan(6) = 2.02 (measured 1.95). The paper's model is not the
// light's visibility: a cube's mean extinction enters exp(), so behind an
// opaque edge the penumbra is narrower than the light's 1.3741 d tan(theta)
// (measured 0.64 of it at 6 degrees, 0.61 at 12, 0.47 at 3 where the 4-voxel
// step and the table's cells dominate).
TEST(ConeShadows, EdgePenumbraScalesWithTheLightsAngle) {
  auto width = [](float theta) {
    Light light;
    light.type = LightType::Distant;
    light.angle_deg = theta;
    const testing::EdgeScene edge = testing::edge_scene(light, 60.0f);
    // The cone march itself (the floor's cache, FloorPixelsReadThePlaneCaches, widens it by 1-3 %).
    return testing::penumbra_width_10_90(edge, render_with(edge.scene, "cone-shadows", {{"shadow_cache", false}}),
                                         testing::unshadowed_floor(edge));
  };
  const float w6 = width(6.0f), w12 = width(12.0f);
  const float analytic6 = 1.3741f * 60.0f * std::tan(glm::radians(6.0f));
  EXPECT_NEAR(w12 / w6, std::tan(glm::radians(12.0f)) / std::tan(glm::radians(6.0f)), 0.1f);
  EXPECT_NEAR(w6 / analytic6, 0.64f, 0.06f);
}

}  // namespace
}  // namespace penumbra

namespace penumbra {
namespace {

// The floor's shadow caches (sat_common/plane_caches.h) against the cone
// march they stand for, at random floor points over three times the box's
// width: bilinear between nodes a voxel apart inside the rectangle the
// box projects to, and exactly the march's 1 outside it; for a directional
// light and a point light above the box; none where the shadow has no bound
// or needs too large a grid.
TEST(ConeShadows, PlaneCachesMatchTheConeMarchOnTheFloor) {
  Scene scene = spheres_over_floor(32);
  SceneResources resources;
  resources.update(scene);
  VolumeAlignedTable table("test");
  table.update(scene, resources, 1.0);
  const Box3 box = scene.volume().world_box();
  const ConeMarch cone{table.view(), table.grid(), box, std::tan(glm::radians(5.0f)), 4.0f, 1.0f};
  Light point;
  point.type = LightType::Point;
  point.position = vec3(10.0f, -6.0f, box.upper.z + 40.0f);
  const Plane floor{vec3(0.0f, 0.0f, box.lower.z - 6.0f), vec3(0.0f, 0.0f, 1.0f), vec3(0.8f)};
  for (const Light& light : {scene.lights()[0], point}) {
    PlaneCaches caches;
    const std::vector<Light> lights = {light};
    ASSERT_TRUE(caches.update(lights, {floor}, box, 1.0f, 1, [&](int, vec3 p) {
      return cone.transmittance(0, p, sample_light(light, p));
    }));
    EXPECT_FALSE(caches.update(lights, {floor}, box, 1.0f, 1, [](int, vec3) { return 0.0f; })) << "nothing changed";
    const PlaneCachesView view = caches.view();
    ASSERT_TRUE(view.has(0, 0));
    Pcg32 rng(5);
    double worst = 0.0, sum = 0.0, outside = 0.0;
    int shadowed = 0;
    const int n = 4000;
    for (int i = 0; i < n; ++i) {
      const vec3 p(box.lower.x + (3.0f * rng.next_float() - 1.0f) * box.extent().x,
                   box.lower.y + (3.0f * rng.next_float() - 1.0f) * box.extent().y, floor.point.z);
      const float cached = view.sample(0, 0, p);
      const float march = cone.transmittance(0, p, sample_light(light, p));
      worst = std::max(worst, double(std::abs(cached - march)));
      sum += std::abs(cached - march);
      shadowed += march < 0.9f ? 1 : 0;
      if (cached == 1.0f) outside = std::max(outside, double(1.0f - march));
    }
    std::printf("[cone-shadows plane cache] %s light: mean error %.5f, worst %.4f, %d of %d points shadowed\n",
                light.type == LightType::Point ? "point" : "directional", sum / n, worst, shadowed, n);
    EXPECT_GT(shadowed, n / 50);
    EXPECT_LT(sum / n, 1e-3);
    EXPECT_LT(worst, 0.05);
    EXPECT_LT(outside, 1e-6) << "outside the rectangle the march sees nothing";
  }
  // A point light below the box's top: the shadow has no bound, no grid.
  point.position.z = box.upper.z - 1.0f;
  PlaneCaches none;
  none.update({point}, {floor}, box, 2.0f, 1, [](int, vec3) { return 0.0f; });
  EXPECT_FALSE(none.view().has(0, 0));
  // A directional light 1 degree above the floor's horizon: a rectangle of
  // thousands of voxels, no grid either.
  Light grazing;
  grazing.direction = glm::normalize(vec3(1.0f, 0.0f, -std::tan(glm::radians(1.0f))));
  PlaneCaches flat;
  flat.update({grazing}, {floor}, box, 1.0f, 1, [](int, vec3) { return 0.0f; });
  EXPECT_FALSE(flat.view().has(0, 0));
}

// The technique reads the floor's caches (a floor-only view of the volume's
// long shadow under a low light: every pixel a plane hit), close to the per
// pixel cone march; a floor move rebuilds no table or 3D cache (rebuilds())
// but the floor's caches, so the image equals a fresh technique's.
TEST(ConeShadows, FloorPixelsReadThePlaneCaches) {
  Scene scene = spheres_over_floor(32);
  Light low = scene.lights()[0];
  low.direction = glm::normalize(vec3(1.0f, 0.3f, -0.6f));
  scene.set_lights({low});
  const Box3 box = scene.volume().world_box();
  const vec3 shadow(box.upper.x + 0.8f * box.extent().x, box.center().y + 0.2f * box.extent().y, box.lower.z);
  scene.set_camera(Camera{shadow + vec3(0.0f, -2.0f, 60.0f), shadow, vec3(0.0f, 1.0f, 0.0f), 40.0f});
  const Image direct = render_with(scene, "cone-shadows", {{"shadow_cache", false}});
  const TechniqueInfo& info = find_technique("cone-shadows");
  ParameterValues params(info.parameters);
  auto t = info.create();
  t->prepare(scene, params);
  Image cached;
  t->render(scene, cached);
  const ImageComparison d = compare_images(cached, direct);
  std::printf("[cone-shadows plane cache] floor view: mean dE %.3f, p99 %.3f, max %.3f, rmse %.5f\n", d.mean_de,
              d.p99_de, d.max_de, rmse(cached, direct));
  EXPECT_GT(rmse(direct, render_with(scene, "phong")), 0.02) << "the view shows a shadow";
  EXPECT_LT(d.p99_de, 1.0);
  EXPECT_GT(d.max_de, 0.1) << "the cache is read (bilinear, not the march)";
  // The edge's penumbra on the floor, cached against the march: measured
  // 5.65 against 5.51 voxels at 6 degrees, 10.84 against 10.76 at 12.
  for (const float theta : {6.0f, 12.0f}) {
    Light light;
    light.type = LightType::Distant;
    light.angle_deg = theta;
    const testing::EdgeScene edge = testing::edge_scene(light, 60.0f);
    const Image unshadowed = testing::unshadowed_floor(edge);
    const float w_cached = testing::penumbra_width_10_90(edge, render_with(edge.scene, "cone-shadows"), unshadowed);
    const float w_direct = testing::penumbra_width_10_90(
        edge, render_with(edge.scene, "cone-shadows", {{"shadow_cache", false}}), unshadowed);
    EXPECT_NEAR(w_cached / w_direct, 1.0f, 0.04f) << theta;
  }
  const std::uint64_t before = t->rebuilds();
  scene.set_planes({Plane{vec3(0.0f, 0.0f, box.lower.z - 8.0f), vec3(0.0f, 0.0f, 1.0f), vec3(0.8f)}});
  t->prepare(scene, params);
  EXPECT_EQ(t->rebuilds(), before);
  Image moved;
  t->render(scene, moved);
  EXPECT_EQ(rmse(moved, render_with(scene, "cone-shadows")), 0.0);
}

}  // namespace
}  // namespace penumbra

// shadow-rays against analytic and independent computations.
#include "penumbra/render/lighting.h"
#include "penumbra/render/render_loop.h"
#include "penumbra/render/scene_resources.h"
#include "penumbra/analysis/image_metrics.h"
#include "penumbra/techniques/registry.h"
#include "test_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace penumbra {
namespace {

using testing::procedural_scene;
using testing::render_with;

Scene lit_spheres(int image_size = 40) {
  Scene scene = procedural_scene("spheres", ivec3(48), image_size);
  scene.set_transfer_function(TransferFunction({{0.0f, vec3(1.0f, 0.6f, 0.3f), 0.0f},
                                                {0.3f, vec3(1.0f, 0.6f, 0.3f), 0.2f},
                                                {1.0f, vec3(0.9f, 0.9f, 1.0f), 0.8f}}));
  TransferFunction tf = scene.transfer_function();
  tf.set_range(vec2(0.0f, 1.0f));
  scene.set_transfer_function(tf);
  Light light;
  light.direction = glm::normalize(vec3(0.5f, 0.7f, -1.0f));
  scene.set_lights({light});
  return scene;
}

TEST(ShadowRays, ZeroShadowDensityIsUnshadowedSingleScattering) {
  const Scene scene = lit_spheres();
  const Image shadowless = render_with(scene, "shadow-rays", {{"shadow_density_scale", 0.0}});
  SceneResources resources;
  resources.update(scene);
  const RenderView v = resources.view(scene);
  Image expected;
  render_image(v, [&](const auto&) { return ScatteringLighting<NoShadows>{&v, {}, Shading::Phase}; }, expected);
  EXPECT_LT(rmse(shadowless, expected), 1e-6);
  // Shadows darken: with full density the image is darker somewhere.
  const Image shadowed = render_with(scene, "shadow-rays");
  EXPECT_GT(rmse(shadowless, shadowed), 0.01);
}

// A floor under the spheres, lit at 45 degrees, seen from straight above with
// an orthographic camera. The volume is black (it absorbs but scatters
// nothing) and ambient is 0, so a floor pixel outside the volume's footprint
// is exactly cos(45) * T(q -> light). T is computed here independently, by
// integrating the analytic field of the generator (not the voxels) with a
// fine step. Tolerance: 0.01 + 3% of T, for trilinear interpolation of the
// 48^3 grid versus the analytic field and the 0.5-voxel step. With the shadow
// cache a floor point looks up the cache where its shadow ray enters the box;
// the cache (half the voxel resolution by default) adds its interpolation error.
// Measured worst relative errors for the point light (converging shadow rays,
// 1 / d^2 across the floor): 0.008 exact, 0.009 with the voxel-resolution cache.
void expect_floor_shadow_matches_optical_depth(const ParameterSettings& params, float tolerance,
                                               float relative, const Light& light = Light{}) {
  const ivec3 size(48);
  Scene scene = procedural_scene("spheres", size, 64);
  TransferFunction tf({{0.0f, vec3(0.0f), 0.0f}, {1.0f, vec3(0.0f), 0.5f}});
  tf.set_range(vec2(0.0f, 1.0f));
  scene.set_transfer_function(tf);
  scene.set_lights({light});
  Material m;
  m.ambient = 0.0f;
  scene.set_material(m);
  const float floor_z = scene.volume().world_box().lower.z - 15.0f;
  scene.set_planes({Plane{vec3(0.0f, 0.0f, floor_z), vec3(0.0f, 0.0f, 1.0f), vec3(1.0f)}});
  Camera camera;
  camera.eye = vec3(0.0f, 0.0f, 200.0f);
  camera.target = vec3(0.0f);
  camera.up = vec3(0.0f, 1.0f, 0.0f);
  camera.projection = Projection::Orthographic;
  camera.ortho_height = 200.0f;
  scene.set_camera(camera);
  const Image image = render_with(scene, "shadow-rays", params);

  const Box3 box = scene.volume().world_box();
  const vec3 half = 0.5f * box.extent();
  auto analytic_transmittance = [&](vec3 q, vec3 to_light, float distance) {
    const Interval chord = intersect_box(Ray{q, to_light}, box, 0.0f, distance);
    if (chord.empty()) return 1.0f;
    double depth = 0.0;
    const float dt = 0.05f;
    for (float t = chord.t0 + 0.5f * dt; t < chord.t1; t += dt) {
      const vec3 p = (q + t * to_light - box.center()) / half;  // normalised coordinates
      const float v = procedural_value("spheres", p, size);
      depth += -std::log(1.0 - 0.5 * double(v)) * dt;
    }
    return float(std::exp(-depth));
  };
  const CameraView view = scene.camera().view();
  int checked = 0, in_shadow = 0;
  float worst = 0.0f;  // relative error beyond the absolute tolerance
  for (int py = 0; py < 64; py += 2) {
    for (int px = 0; px < 64; px += 2) {
      const Ray ray = view.pixel_ray(float(px) + 0.5f, float(py) + 0.5f, 64, 64);
      const vec3 q = ray.at((ray.origin.z - floor_z) / -ray.direction.z);
      if (std::abs(q.x) <= half.x + 1.0f && std::abs(q.y) <= half.y + 1.0f) continue;  // viewed through the volume
      const LightSample ls = sample_light(light, q);
      const float expected =
          ls.radiance.r * glm::max(0.0f, ls.to_light.z) * analytic_transmittance(q, ls.to_light, ls.distance);
      ASSERT_NEAR(image.at(px, py).r, expected, tolerance + relative * expected)
          << "floor point " << q.x << ", " << q.y;
      worst = glm::max(worst, (std::abs(image.at(px, py).r - expected) - tolerance) / expected);
      ++checked;
      in_shadow += expected < 0.5f * ls.radiance.r * ls.to_light.z;
    }
  }
  std::printf("floor shadow, %s light: %d points, %d in shadow, worst relative error %.3f\n",
              light.type == LightType::Point ? "point" : "directional", checked, in_shadow, worst);
  EXPECT_GT(checked, 200);
  EXPECT_GT(in_shadow, 5);  // the test sees a real shadow, not only lit floor
}

Light light_at_45_degrees() { return testing::directional_light(vec3(1.0f, 0.0f, -1.0f)); }

// A point light above and to the side: the shadow rays converge, and the
// light's radiance falls off as 1 / d^2 across the floor (intensity chosen so
// that the floor under the volume sees about 1).
Light point_light_above() {
  Light light = testing::point_light(vec3(-60.0f, 10.0f, 70.0f));
  light.intensity = 10000.0f;
  return light;
}

TEST(ShadowRays, FloorShadowMatchesIndependentOpticalDepth) {
  expect_floor_shadow_matches_optical_depth({}, 0.01f, 0.03f, light_at_45_degrees());
  expect_floor_shadow_matches_optical_depth({}, 0.01f, 0.02f, point_light_above());
}

// Measured worst error (in units of T after the 0.01): 0.029 exact, 0.029 with
// a cache at voxel resolution (the lookup where the ray enters the box is as
// good as the ray), 0.20 at the default half resolution (the cache's blur of
// the spheres' shadow edges, the same inside the volume).
TEST(ShadowRays, CachedFloorShadowMatchesIndependentOpticalDepth) {
  const ParameterSettings voxel_cache{{"shadow_cache", true}, {"cache_resolution", 1.0}};
  expect_floor_shadow_matches_optical_depth(voxel_cache, 0.01f, 0.04f, light_at_45_degrees());
  expect_floor_shadow_matches_optical_depth({{"shadow_cache", true}}, 0.01f, 0.25f, light_at_45_degrees());
  expect_floor_shadow_matches_optical_depth(voxel_cache, 0.01f, 0.02f, point_light_above());
}

TEST(ShadowRays, CacheApproximatesExactShadowsAndRebuildsOnlyWhenNeeded) {
  Scene scene = lit_spheres();
  const TechniqueInfo& info = find_technique("shadow-rays");
  ParameterValues params(info.parameters);
  params.set("shadow_cache", true);
  params.set("cache_resolution", 1.0);
  auto t = info.create();
  t->prepare(scene, params);
  EXPECT_EQ(t->rebuilds(), 1u);
  EXPECT_EQ(t->aux_bytes(), 48u * 48u * 48u * sizeof(float));
  Image cached;
  t->render(scene, cached);
  const Image exact = render_with(scene, "shadow-rays");
  // Trilinear interpolation of transmittance at voxel resolution: small error.
  EXPECT_LT(rmse(cached, exact), 0.01);

  Camera camera = scene.camera();
  camera.orbit(10.0f, 0.0f);
  scene.set_camera(camera);
  t->prepare(scene, params);
  EXPECT_EQ(t->rebuilds(), 1u) << "a camera move must not rebuild the cache";
  scene.set_material(Material{});
  t->prepare(scene, params);
  EXPECT_EQ(t->rebuilds(), 1u) << "a material change must not rebuild the cache";
  scene.set_lights(scene.lights());
  t->prepare(scene, params);
  EXPECT_EQ(t->rebuilds(), 2u);
  scene.set_transfer_function(scene.transfer_function());
  t->prepare(scene, params);
  EXPECT_EQ(t->rebuilds(), 3u);
  params.set("cache_resolution", 0.5);
  t->prepare(scene, params);
  EXPECT_EQ(t->rebuilds(), 4u);
  EXPECT_EQ(t->aux_bytes(), 24u * 24u * 24u * sizeof(float));
}

TEST(ShadowRays, PointLightInsideTheVolumeIsFiniteAndFallsOff) {
  Scene scene = lit_spheres();
  Light point;
  point.type = LightType::Point;
  point.position = vec3(0.0f);
  point.intensity = 200.0f;
  scene.set_lights({point});
  const Image image = render_with(scene, "shadow-rays");
  for (const vec4& p : image.pixels()) {
    ASSERT_TRUE(std::isfinite(p.r) && std::isfinite(p.g) && std::isfinite(p.b));
  }
  SceneResources resources;
  resources.update(scene);
  const RenderView v = resources.view(scene);
  RayStats stats;
  // Transmittance toward the point light stops at the light.
  const Ray ray{vec3(20.0f, 0.0f, 0.0f), vec3(-1.0f, 0.0f, 0.0f)};
  const float to_light = march_transmittance(v, ray, 20.0f, 1.0f, stats);
  const float through = march_transmittance(v, ray, kInfinity, 1.0f, stats);
  EXPECT_GT(to_light, through);
}

TEST(ShadowRays, LightColourTintsTheImage) {
  Scene scene = lit_spheres();
  Light red = scene.lights()[0];
  red.color = vec3(1.0f, 0.0f, 0.0f);
  scene.set_lights({red});
  Material m;
  m.ambient = 0.0f;
  scene.set_material(m);
  const Image image = render_with(scene, "shadow-rays");
  const vec3 mean = testing::mean_rgb(image, 0, 0, image.width(), image.height());
  EXPECT_GT(mean.r, 0.01f);
  EXPECT_LT(mean.g, 1e-6f);
  EXPECT_LT(mean.b, 1e-6f);
}

TEST(ShadowRays, ForwardScatteringBrightensABacklitVolume) {
  Scene scene = lit_spheres();
  // Light travelling toward the camera (camera looks along +y).
  Light back;
  back.direction = vec3(0.0f, -1.0f, 0.0f);
  scene.set_lights({back});
  Material m;
  m.ambient = 0.0f;
  scene.set_material(m);
  const Image iso = render_with(scene, "shadow-rays", {{"shadow_density_scale", 0.0}});
  m.phase_g = 0.7f;
  scene.set_material(m);
  const Image forward = render_with(scene, "shadow-rays", {{"shadow_density_scale", 0.0}});
  const float a = luminance(testing::mean_rgb(iso, 0, 0, 40, 40));
  const float b = luminance(testing::mean_rgb(forward, 0, 0, 40, 40));
  // HG at cos = 1: (1 - g^2) / (1 - g)^3 = (1 + g) / (1 - g)^2 = 18.9 for g = 0.7.
  EXPECT_NEAR(b / a, 1.7f / 0.09f, 0.05f * 1.7f / 0.09f);
}

}  // namespace
}  // namespace penumbra

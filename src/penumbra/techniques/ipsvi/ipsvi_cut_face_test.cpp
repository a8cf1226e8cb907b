// ipsvi's texel artefacts (issue 21).
//
// On a cut face that the light grazes: the engine CT cut by
// a clip plane, the light 84 degrees from the face's normal. There the light
// rays of neighbouring cache texels enter the cut at depths many steps
// apart and a surface point lies beside texels written just ahead of it; the
// cache grid then showed on the face as stripes and checks. Texels now start
// at the earliest entry of their 3x3 neighbourhood and the cache trails the
// samples that write it by kCacheTrailTexels (sweep_renderer.cpp).
// Against exact shadow rays at 128², mean / p99 dE, measured:
//   line_width 1:  0.574 / 9.01 before, 0.178 / 3.03 after
//   line_width 16: 0.219 / 4.68 before, 0.058 / 1.45 after
// Bounds: about 1.5x the values after, so that either part removed fails.
// The error still falls with the line width (about 2x in p99, as before).
#include "penumbra/analysis/image_metrics.h"
#include "penumbra/techniques/ipsvi/sweep_renderer.h"
#include "test_scene.h"

#include <algorithm>

#include <gtest/gtest.h>

#include <cstdio>

namespace penumbra {
namespace {

// ipsvi at its defaults through `renderer`; `reference` gets exact shadow rays.
Image ipsvi_against_exact(const Scene& scene, IpsviRenderer& renderer, Image& reference) {
  reference = testing::render_with(scene, "shadow-rays", {{"shadow_cache", false}});
  renderer.prepare(scene, IpsviSettings{});
  Image ipsvi;
  renderer.render(scene, ipsvi);
  return ipsvi;
}

Scene grazing_cut_engine() {
  Scene scene = testing::repository_scene("scenes/engine.json", 128);
  scene.set_planes({});
  scene.set_clip_planes({vec4(-1.0f, 0.0f, 0.0f, 10.0f)});  // keeps x <= 10: the face at x = 10 faces +x
  Light light;
  light.direction = glm::normalize(vec3(-0.1f, 1.0f, -0.1f));
  light.intensity = 1.4f;
  scene.set_lights({light});
  Camera camera = scene.camera();
  camera.eye = vec3(420.0f, -120.0f, 120.0f);
  camera.target = vec3(0.0f, 0.0f, -10.0f);
  camera.up = vec3(0.0f, 0.0f, 1.0f);
  camera.fov_deg = 30.0f;
  scene.set_camera(camera);
  return scene;
}

TEST(IpsviCutFace, GrazingLightShowsNoCacheGridPattern) {
  const Scene scene = grazing_cut_engine();
  const Image reference = testing::render_with(scene, "shadow-rays", {{"shadow_cache", false}});
  const int widths[2] = {1, 16};
  const double max_mean[2] = {0.27, 0.09};
  const double max_p99[2] = {4.5, 2.2};
  for (int i = 0; i < 2; ++i) {
    const Image ipsvi = testing::render_with(scene, "ipsvi", {{"line_width", double(widths[i])}});
    if (i == 0) testing::save_test_image(ipsvi, "ipsvi-grazing-cut-face.png");
    const DeltaEStats de = delta_e_stats(ipsvi, reference);
    std::printf("grazing cut face, line_width %d: mean dE %.3f, p99 %.2f\n", widths[i], de.mean, de.p99);
    EXPECT_LT(de.mean, max_mean[i]);
    EXPECT_LT(de.p99, max_p99[i]);
  }
}

// Along floor-shadow edges: opaque spheres over a floor, seen from close
// by. A floor point reads four texels whose light rays pass up to a texel
// beside its own (longer along the view), written after the spheres, so the
// bilinear read spread each shadow edge over that footprint: a one-texel
// ring inside every shadow, brighter than under shadow-rays. Plane hits
// whose texels disagree now march their own light ray (plane_light).
// Measured over the floor pixels of the shadow edges' dark side (3x3
// neighbourhood in shadow-rays spanning over 20 % of the lit floor), the
// mean excess of ipsvi over exact shadow rays in units of the lit floor:
// 0.046 with the edge march off (threshold infinite, as before), 0.00007
// with it; 110 of the 3217 floor pixels march.
TEST(IpsviFloorShadow, EdgesShowNoBrightOutline) {
  Scene scene = testing::with_floor(testing::lit_spheres(64));
  TransferFunction tf({{0.0f, vec3(1.0f), 0.0f},
                       {0.3f, vec3(1.0f), 0.0f},
                       {0.34f, vec3(0.9f, 0.8f, 0.7f), 0.95f},
                       {1.0f, vec3(0.9f, 0.8f, 0.7f), 0.95f}});
  tf.set_range(vec2(0.0f, 1.0f));
  scene.set_transfer_function(tf);
  scene.set_lights({testing::directional_light(vec3(0.5f, 0.7f, -1.0f))});
  Camera camera = scene.camera();
  camera.eye = vec3(-10.0f, -50.0f, 30.0f);
  camera.target = vec3(16.0f, 22.0f, scene.planes()[0].point.z);
  camera.up = vec3(0.0f, 0.0f, 1.0f);
  camera.fov_deg = 35.0f;
  scene.set_camera(camera);
  Image reference;
  IpsviRenderer renderer;
  const Image ipsvi = ipsvi_against_exact(scene, renderer, reference);
  testing::save_test_image(ipsvi, "ipsvi-floor-shadow-edges.png");
  Scene volume_only = scene;
  volume_only.set_planes({});
  const Image volume = testing::render_with(volume_only, "shadow-rays", {{"shadow_cache", false}});

  const int n = 64;
  auto lum = [](const Image& image, int x, int y) { return luminance(vec3(image.at(x, y))); };
  auto on_floor = [&](int x, int y) { return volume.at(x, y).a < 0.01f; };
  float lit = 0.0f;
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      if (on_floor(x, y)) lit = std::max(lit, lum(reference, x, y));
    }
  }
  double excess = 0.0;
  int dark = 0, floor_pixels = 0;
  for (int y = 1; y + 1 < n; ++y) {
    for (int x = 1; x + 1 < n; ++x) {
      if (!on_floor(x, y)) continue;
      ++floor_pixels;
      float lo = lit, hi = 0.0f;
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          lo = std::min(lo, lum(reference, x + dx, y + dy));
          hi = std::max(hi, lum(reference, x + dx, y + dy));
        }
      }
      const float r = lum(reference, x, y);
      if (hi - lo <= 0.2f * lit || r >= 0.5f * (lo + hi)) continue;
      excess += (lum(ipsvi, x, y) - r) / lit;
      ++dark;
    }
  }
  excess /= std::max(dark, 1);
  const std::uint64_t exact = renderer.last_counts().exact_plane_rays;
  std::printf("floor-shadow edges: %d dark-side pixels of %d on the floor, mean excess over shadow-rays %.5f of the "
              "lit floor; %llu plane hits marched their own light ray\n",
              dark, floor_pixels, excess, (unsigned long long)exact);
  EXPECT_GT(dark, 50);
  EXPECT_LT(excess, 0.0003);
  EXPECT_LT(double(exact), 0.05 * floor_pixels) << "only the edges march";
}

// Zoomed in (issue 21): the automatic cache stays within its texel budget
// (1.4 per image pixel), so its memory holds from fov 32 down to fov 3, and
// the image against exact shadow rays stays close. On the engine CT at 96^2,
// measured (aux MB, its ratio to fov 32's, mean / p99 dE):
//   budget            fov 32                 fov 9                  fov 3
//   none (before)     0.50, 1.00, 0.07/1.75  1.52, 3.04, 0.19/3.06  2.37, 4.75, 0.04/0.77
//   1.4 (default)     0.50, 1.00, 0.07/1.75  0.66, 1.33, 0.29/4.62  0.67, 1.34, 0.04/0.81
// The price is at middle zoom, where texels grow to about 1.5 pixels across. With
// the budget ignored the memory check fails at fov 9 and 3.
// Renders `scene` zoomed to fov 32, 9 and 3 with ipsvi and exact shadow
// rays: the aux memory must stay within 1.5x of fov 32's and the dE within
// the bounds.
void expect_zoom_holds(Scene scene, const char* name, const double max_mean[3], const double max_p99[3]) {
  std::uint64_t bytes_at_32 = 0;
  const float fovs[3] = {32.0f, 9.0f, 3.0f};
  for (int i = 0; i < 3; ++i) {
    const float fov = fovs[i];
    Camera camera = scene.camera();
    camera.fov_deg = fov;
    scene.set_camera(camera);
    Image reference;
    IpsviRenderer renderer;
    const Image ipsvi = ipsvi_against_exact(scene, renderer, reference);
    const DeltaEStats de = delta_e_stats(ipsvi, reference);
    const std::uint64_t bytes = renderer.aux_bytes();
    if (fov == 32.0f) bytes_at_32 = bytes;
    const int side = ipsvi_cache_size(scene, IpsviSettings{});
    std::printf("%s fov %4.1f, 96^2: cache side %d, aux %.3f MB (%.2fx fov 32), mean dE %.3f, p99 %.2f\n", name, fov,
                side, double(bytes) / 1e6, double(bytes) / double(bytes_at_32), de.mean, de.p99);
    EXPECT_LE(double(bytes), 1.5 * double(bytes_at_32)) << name << ", fov " << fov;
    EXPECT_LT(de.mean, max_mean[i]) << name << ", fov " << fov;
    EXPECT_LT(de.p99, max_p99[i]) << name << ", fov " << fov;
  }
}

TEST(IpsviZoom, CacheMemoryHoldsAndErrorStaysSmallDownToFov3) {
  const double max_mean[3] = {0.1, 0.4, 0.08}, max_p99[3] = {2.3, 6.5, 1.4};
  expect_zoom_holds(testing::repository_scene("scenes/engine.json", 96), "engine", max_mean, max_p99);
}

// The same with a point light inside the box (an octahedral map). Where the
// light is in view every direction is needed: the whole map, at most 4
// texels per image pixel. Zoomed in away from it (the light off the view
// axis at fov 3), only the directions toward what the camera sees of the
// box, in the same budget. Measured (aux MB, mean / p99 dE):
//   light          fov 32                          fov 9                fov 3
//   off the axis   before 1.96, 0.06/1.23          17.25, 0.31/1.83     17.25, 0.50/7.56
//                  after  1.92, 0.058/1.22         1.92, 0.340/1.87     1.86 (a part), 0.565/8.88
//   on the axis    before 1.96, 0.09/1.46          17.25, 0.39/2.54     17.25, 0.58/7.56
//                  after  1.92, 0.093/1.47         1.92, 0.397/2.70     1.92, 0.592/7.56
// ("before": the map of all directions with texels a pixel wide, up to 6x
// the image side). Bounds about 1.5x the values after. The large p99 at fov
// 3 is the cache's texels along one shadow edge, before as after.
TEST(IpsviZoom, ALightInsideTheBoxKeepsTheCacheMemoryDownToFov3) {
  const vec3 positions[2] = {vec3(75.0f, -40.0f, 40.0f), vec3(35.0f, -35.0f, 10.0f)};
  const char* names[2] = {"light off the axis", "light on the axis"};
  const double max_mean[2][3] = {{0.09, 0.5, 0.85}, {0.14, 0.6, 0.9}};
  const double max_p99[2][3] = {{1.8, 2.8, 13.0}, {2.2, 4.0, 11.3}};
  for (int i = 0; i < 2; ++i) {
    Scene scene = testing::repository_scene("scenes/engine.json", 96);
    Light light;
    light.type = LightType::Point;
    light.position = positions[i];
    light.intensity = 8000.0f;
    scene.set_lights({light});
    expect_zoom_holds(scene, names[i], max_mean[i], max_p99[i]);
  }
}

}  // namespace
}  // namespace penumbra

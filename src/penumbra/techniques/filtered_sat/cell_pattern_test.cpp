// The cell-periodic pattern of issue 22: a flat lit face under a light that
// is not aligned with the data axes, seen from the front. The face is
// uniform (a clip plane through a homogeneous medium), so every structure a
// technique draws on it is an artefact. Its energy is the mean squared
// difference, in CIELAB L*, between each pixel and the mean of its 5 x 5
// neighbourhood, over the middle of the face: a table whose cells the face
// cuts as a staircase shows a pattern with the period of one cell there.
#include "penumbra/analysis/color_space.h"
#include "test_scene.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <vector>

namespace penumbra {
namespace {

using testing::procedural_scene;
using testing::render_with;

// A 40^3 homogeneous medium cut by the clip plane z <= 4 (so its top face
// lies across the cells of any table), lit along a direction that is not
// near any data axis, seen from straight above by an orthographic camera
// that frames 16 x 16 voxels of the face at 64 x 64 pixels (4 pixels per
// voxel, enough to resolve a one-cell period).
Scene lit_cut_face(float alpha = 0.5f) {
  Scene scene = procedural_scene("slab", ivec3(40), 64);
  scene.set_transfer_function(testing::step_tf(0.0f, vec3(0.8f), alpha));
  scene.set_clip_planes({vec4(0.0f, 0.0f, -1.0f, 4.0f)});  // keep dot((0, 0, -1), p) + 4 >= 0
  Light light;
  light.direction = glm::normalize(vec3(0.45f, 0.3f, -1.0f));
  scene.set_lights({light});
  Material m;
  m.ambient = 0.0f;
  scene.set_material(m);
  Camera camera;
  camera.eye = vec3(0.0f, 0.0f, 40.0f);
  camera.target = vec3(0.0f, 0.0f, 0.0f);
  camera.up = vec3(0.0f, 1.0f, 0.0f);
  camera.projection = Projection::Orthographic;
  camera.ortho_height = 16.0f;
  scene.set_camera(camera);
  return scene;
}

double pattern_energy(const Image& image) {
  const int w = image.width(), h = image.height();
  std::vector<double> l(std::size_t(w) * std::size_t(h));
  for (int i = 0; i < w * h; ++i) {
    l[std::size_t(i)] = srgb_linear_to_lab(glm::clamp(vec3(image.data()[i]), vec3(0.0f), vec3(1.0f))).l;
  }
  double energy = 0.0;
  int count = 0;
  for (int y = 4; y < h - 4; ++y) {
    for (int x = 4; x < w - 4; ++x) {
      double mean = 0.0;
      for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx) mean += l[std::size_t((y + dy) * w + x + dx)];
      const double d = l[std::size_t(y * w + x)] - mean / 25.0;
      energy += d * d;
      ++count;
    }
  }
  return energy / count;
}

TEST(FilteredSatCellPattern, LitCutFaceUnderARotatedLightShowsNoCellPattern) {
  const Scene scene = lit_cut_face();
  const Image reference = render_with(scene, "shadow-rays", {{"shadow_cache", false}});
  testing::save_test_image(reference, "cell-pattern-shadow-rays.png");
  const double floor = pattern_energy(reference);
  std::printf("shadow-rays: pattern energy %.4f\n", floor);
  for (const double filter : {1.0, 3.0}) {
    const Image image = render_with(scene, "filtered-sat", {{"filter_voxels", filter}, {"shadow_cache", false}});
    testing::save_test_image(image, "cell-pattern-filter-" + std::to_string(int(filter)) + ".png");
    const double energy = pattern_energy(image);
    std::printf("filtered-sat filter %.0f: pattern energy %.4f\n", filter, energy);
    // Measured at the default table resolution (1 cell per voxel): 0.059
    // and 0.016 L*^2 at filters 1 and 3 (shadow-rays 0); with the cells
    // holding their centre's value instead of their mean, 1.22 and 0.037.
    EXPECT_LT(energy - floor, filter == 1.0 ? 0.15 : 0.03) << "filter " << filter;
  }
}

}  // namespace
}  // namespace penumbra

namespace penumbra {
namespace {

// Issue 22, self-shadowing: the patch of the paper's cuboid starts at full
// width in the sample's plane, so on a face lit obliquely half of it lies in
// the material below the face, and the face darkens as the filter grows.
// Starting the volume a half-width toward the light (patch_offset = 1)
// leaves that material out, and with it every other occluder within that
// distance: the material between a sample below the face and the face
// itself, so the face comes out brighter than shadow-rays draw it (measured:
// an opaque face 51 L* with shadow-rays, 23 with the paper's cuboid at
// filter 7, 91 with the offset; a translucent one 67 and 88; through an SSAT, a
// point light on the same line: 51, 27, 91). Hence the
// option is off by default (docs/filtered-sat.md, "Self-shadowing").
TEST(FilteredSatCellPattern, PatchOffsetLiftsTheSelfShadowingOfALitFace) {
  for (const float alpha : {0.99f, 0.5f}) {
    const Scene scene = lit_cut_face(alpha);
    auto lightness = [](const Image& image) { return srgb_linear_to_lab(testing::mean_rgb(image, 8, 8, 56, 56)).l; };
    const double reference = lightness(render_with(scene, "shadow-rays", {{"shadow_cache", false}}));
    const double paper = lightness(render_with(scene, "filtered-sat", {{"filter_voxels", 7.0}}));
    const double offset =
        lightness(render_with(scene, "filtered-sat", {{"filter_voxels", 7.0}, {"patch_offset", 1.0}}));
    std::printf("alpha %.2f, lit face L*: shadow-rays %.2f, filter 7 %.2f, with patch_offset 1 %.2f\n", alpha,
                reference, paper, offset);
    EXPECT_GT(reference - paper, 3.0) << "the paper's cuboid darkens the face";
    EXPECT_GT(offset, reference) << "the offset leaves no self-shadowing";
  }
  // The same through an SSAT: a point light along the same oblique direction.
  Scene scene = lit_cut_face(0.99f);
  Light point;
  point.type = LightType::Point;
  point.position = vec3(0.0f, 0.0f, 4.0f) - 60.0f * scene.lights()[0].direction;
  point.intensity = 3600.0f;
  scene.set_lights({point});
  auto lightness = [](const Image& image) { return srgb_linear_to_lab(testing::mean_rgb(image, 8, 8, 56, 56)).l; };
  const double reference = lightness(render_with(scene, "shadow-rays", {{"shadow_cache", false}}));
  const double paper = lightness(render_with(scene, "filtered-sat", {{"filter_voxels", 7.0}}));
  const double offset = lightness(render_with(scene, "filtered-sat", {{"filter_voxels", 7.0}, {"patch_offset", 1.0}}));
  std::printf("point light, lit face L*: shadow-rays %.2f, filter 7 %.2f, with patch_offset 1 %.2f\n", reference,
              paper, offset);
  EXPECT_GT(reference - paper, 3.0);
  EXPECT_GT(offset, reference);
}

}  // namespace
}  // namespace penumbra

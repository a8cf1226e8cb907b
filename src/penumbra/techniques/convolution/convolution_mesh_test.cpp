// convolution with meshes (Patel et al. 2013, section 4): the layered depth
// image, the per-mesh parity, the mesh medium's integration, its shadows and
// its highlight, checked against Beer-Lambert on spheres whose chords are
// known in closed form.
#include "penumbra/analysis/image_metrics.h"
#include "penumbra/render/microfacet.h"
#include "penumbra/scene/mesh_shapes.h"
#include "test_scene.h"

#include <gtest/gtest.h>

#include <cmath>

namespace penumbra {
namespace {

using testing::procedural_scene;
using testing::render_with;

constexpr float kAlphaPerUnit = 0.1f;  // mesh TF opacity per world unit
const float kSigma = -std::log(1.0f - kAlphaPerUnit);

// A sphere mesh of `radius` at `center` filled with a homogeneous white medium
// (constant detail through a constant TF of alpha `alpha` per world unit).
MeshObject homogeneous_sphere(float radius, vec3 center, float alpha = kAlphaPerUnit) {
  MeshObject m;
  m.source.builtin = "sphere";
  m.mesh = make_builtin_mesh("sphere", 4);  // 5120 triangles: radial error < 1e-3 R
  m.scale = vec3(radius);
  m.translate = center;
  m.material.detail.type = DetailType::Constant;
  TransferFunction tf({{0.0f, vec3(1.0f), alpha}, {1.0f, vec3(1.0f), alpha}});
  tf.set_unit_length(1.0f);
  m.material.tf = tf;
  m.material.specular = 0.0f;
  return m;
}

// An empty 32^3 volume (box [-15.5, 15.5]^3) seen from +z by an orthographic
// camera `height` world units tall, lit by nothing but `ambient`.
Scene mesh_scene(int image, float height, float ambient) {
  Scene scene = procedural_scene("empty", ivec3(32), image);
  Camera cam;
  cam.projection = Projection::Orthographic;
  cam.eye = vec3(0.0f, 0.0f, 100.0f);
  cam.target = vec3(0.0f);
  cam.up = vec3(0.0f, 1.0f, 0.0f);
  cam.ortho_height = height;
  scene.set_camera(cam);
  scene.set_lights({});
  Material m;
  m.ambient = ambient;
  scene.set_material(m);
  return scene;
}

// World (x, y) of a pixel centre for the camera above (x right, y up).
vec2 pixel_world(int x, int y, int image, float height) {
  const float px = height / float(image);
  return vec2((float(x) + 0.5f) * px - 0.5f * height, 0.5f * height - (float(y) + 0.5f) * px);
}

float chord(float radius, vec2 offset) {
  const float r2 = glm::dot(offset, offset);
  return r2 < radius * radius ? 2.0f * std::sqrt(radius * radius - r2) : 0.0f;
}

// Opacity through the sphere is 1 - exp(-sigma chord) at every pixel; a second
// sphere nested inside the first adds its own optical depth (per-mesh parity:
// one parity bit for both would call the inner sphere "outside").
TEST(ConvolutionMeshes, NestedHomogeneousSpheresFollowBeerLambert) {
  constexpr int kImage = 48;
  constexpr float kHeight = 32.0f;
  Scene scene = mesh_scene(kImage, kHeight, 1.0f);
  scene.set_meshes({homogeneous_sphere(12.0f, vec3(0.0f)), homogeneous_sphere(5.0f, vec3(2.0f, 1.0f, 0.0f), 0.3f)});
  const Image image = render_with(scene, "convolution");
  testing::save_test_image(image, "conv_mesh_nested_spheres.png");
  const float sigma_inner = -std::log(1.0f - 0.3f);
  float worst = 0.0f;
  int checked = 0;
  for (int y = 0; y < kImage; ++y) {
    for (int x = 0; x < kImage; ++x) {
      const vec2 p = pixel_world(x, y, kImage, kHeight);
      if (glm::length(p) > 0.9f * 12.0f) continue;  // the rim, where the chord is steep in r
      const float depth = kSigma * chord(12.0f, p) + sigma_inner * chord(5.0f, p - vec2(2.0f, 1.0f));
      const float expected = 1.0f - std::exp(-depth);
      worst = std::max(worst, std::abs(image.at(x, y).a - expected));
      ++checked;
    }
  }
  EXPECT_GT(checked, 500);
  // The coverage of each slab is exact; what is left is the tessellation
  // (chords within ~0.2%) and the inner sphere's rim in pixels that straddle it.
  EXPECT_LT(worst, 0.02f);
}

// The shadow of the sphere on a floor far below, with a tilted directional
// light from behind the viewer. Each slab's re-sampling of the light buffer
// may blur a hard shadow (the blur section 7 of the paper admits), but a blur
// keeps both the shadow's centre and the light it removes: the floor misses lit * integral over the sphere's cross
// section of (1 - exp(-sigma chord)), spread over an area 1 / cos(45 deg)
// larger, and that missing light is centred where the light through the
// sphere's centre meets the floor.
TEST(ConvolutionMeshes, ShadowOnTheFloorRemovesTheBeerLambertLight) {
  constexpr int kImage = 64;
  constexpr float kHeight = 128.0f;
  constexpr float kRadius = 12.0f;
  Scene scene = mesh_scene(kImage, kHeight, 0.0f);
  scene.set_meshes({homogeneous_sphere(kRadius, vec3(0.0f))});
  Light light;
  light.direction = glm::normalize(vec3(1.0f, 0.0f, -1.0f));
  scene.set_lights({light});
  scene.set_planes({Plane{vec3(0.0f, 0.0f, -40.0f), vec3(0.0f, 0.0f, 1.0f), vec3(0.8f)}});
  const Image image = render_with(scene, "convolution");
  testing::save_test_image(image, "conv_mesh_shadow.png");
  const float lit = 0.8f * std::sqrt(0.5f);  // colour * cos(45 deg) * L
  const float pixel_area = (kHeight / kImage) * (kHeight / kImage);
  double missing = 0.0, moment_x = 0.0, moment_y = 0.0;
  for (int y = 0; y < kImage; ++y) {
    for (int x = 0; x < kImage; ++x) {
      const vec2 p = pixel_world(x, y, kImage, kHeight);
      if (p.x < 1.1f * kRadius) continue;  // the sphere itself and the floor left of it
      const double m = (lit - image.at(x, y).r) * pixel_area;
      missing += m;
      moment_x += m * p.x;
      moment_y += m * p.y;
    }
  }
  // 2 pi int_0^R (1 - exp(-2 sigma u)) u du over the cross section, / cos 45.
  const double s = kSigma, R = kRadius;
  const double cross = 2.0 * kPi * (R * R / 2.0 - (1.0 - std::exp(-2.0 * s * R) * (1.0 + 2.0 * s * R)) / (4.0 * s * s));
  const double expected = lit * cross * std::sqrt(2.0);
  std::printf("shadow: missing light %.1f (expected %.1f), centre (%.2f, %.2f)\n", missing, expected,
              moment_x / missing, moment_y / missing);
  // The floor far from the shadow is lit fully.
  EXPECT_NEAR(image.at(kImage - 2, 2).r, lit, 0.005f);
  // 3%: the pixel sum of a shadow 17 units across on 2-unit pixels, and the
  // blur's tail that reaches under the sphere's silhouette.
  EXPECT_NEAR(missing, expected, 0.03 * expected);
  EXPECT_NEAR(moment_x / missing, 40.0, 1.0);  // the light through (0, 0, 0) meets z = -40 at x = 40
  EXPECT_NEAR(moment_y / missing, 0.0, 0.5);
}

// A perspective camera inside a sphere sees its medium on every pixel, up to
// the sphere's surface one radius away.
TEST(ConvolutionMeshes, CameraInsideAMeshSeesItsMediumEverywhere) {
  constexpr int kImage = 24;
  Scene scene = mesh_scene(kImage, 1.0f, 1.0f);
  Camera cam;
  cam.eye = vec3(0.0f);
  cam.target = vec3(0.0f, 0.0f, -1.0f);
  cam.up = vec3(0.0f, 1.0f, 0.0f);
  cam.fov_deg = 60.0f;
  scene.set_camera(cam);
  scene.set_meshes({homogeneous_sphere(10.0f, vec3(0.0f), 0.05f)});
  const Image image = render_with(scene, "convolution");
  const float expected = 1.0f - std::exp(10.0f * std::log(1.0f - 0.05f));
  for (int y = 0; y < kImage; ++y) {
    for (int x = 0; x < kImage; ++x) ASSERT_NEAR(image.at(x, y).a, expected, 0.01f) << x << ", " << y;
  }
}

// The highlight sits where the sphere's normal is the half vector between the
// viewer and the light.
TEST(ConvolutionMeshes, HighlightSitsWhereTheNormalIsTheHalfVector) {
  constexpr int kImage = 64;
  constexpr float kHeight = 32.0f;
  Scene scene = mesh_scene(kImage, kHeight, 0.0f);
  MeshObject sphere = homogeneous_sphere(12.0f, vec3(0.0f), 0.9f);
  Light light;
  light.direction = glm::normalize(vec3(0.5f, -0.3f, -1.0f));
  scene.set_lights({light});
  scene.set_meshes({sphere});
  const Image matte = render_with(scene, "convolution");
  sphere.material.specular = 1.0f;
  sphere.material.roughness = 0.1f;
  scene.set_meshes({sphere});
  const Image shiny = render_with(scene, "convolution");
  testing::save_test_image(shiny, "conv_mesh_highlight.png");
  int best_x = 0, best_y = 0;
  float best = -1.0f;
  for (int y = 0; y < kImage; ++y) {
    for (int x = 0; x < kImage; ++x) {
      const float d = shiny.at(x, y).g - matte.at(x, y).g;
      EXPECT_GE(d, -1e-5f);
      if (d > best) best = d, best_x = x, best_y = y;
    }
  }
  EXPECT_GT(best, 0.1f);
  const vec3 h = glm::normalize(vec3(0.0f, 0.0f, 1.0f) - light.direction);
  const vec2 expected = 12.0f * vec2(h);  // the point of the sphere with normal h, seen from above
  const vec2 found = pixel_world(best_x, best_y, kImage, kHeight);
  EXPECT_LT(glm::length(found - expected), 1.5f) << found.x << ", " << found.y;
}

}  // namespace
}  // namespace penumbra

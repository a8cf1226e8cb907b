// The defined behaviour of awkward inputs (DESIGN.md 5): non-finite voxels,
// empty (fully transparent) volumes, a camera inside the volume, a light
// along the view direction, time steps and jitter.
#include "penumbra/analysis/image_metrics.h"
#include "penumbra/base/error.h"
#include "test_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace penumbra {
namespace {

using testing::procedural_scene;
using testing::render_with;

bool all_finite(const Image& image) {
  for (const vec4& p : image.pixels())
    for (int c = 0; c < 4; ++c)
      if (!std::isfinite(p[c])) return false;
  return true;
}

Scene lit(Scene scene) {
  Light l;
  l.direction = glm::normalize(vec3(0.3f, 0.5f, -1.0f));
  scene.set_lights({l});
  return scene;
}

// NaN and inf voxels sample as transparent: the image stays finite and a slab
// whose middle third is NaN transmits like a slab two thirds as thick.
TEST(EdgeCases, NonFiniteVoxelsAreTransparent) {
  auto volume = std::make_shared<Volume>(ivec3(30, 8, 8), VoxelType::Float32);
  float* d = volume->frame_as<float>(0);
  for (int z = 0; z < 8; ++z)
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 30; ++x) {
        float v = 1.0f;
        if (x >= 10 && x < 20) v = (x % 2) ? std::numeric_limits<float>::quiet_NaN() : std::numeric_limits<float>::infinity();
        d[x + 30 * (y + 8 * z)] = v;
      }
  Scene scene = lit(procedural_scene("slab", ivec3(8), 16));
  scene.set_volume(volume);
  scene.set_transfer_function(testing::step_tf(0.0f, vec3(1.0f), 0.1f));
  Camera c;
  c.eye = vec3(-100.0f, 0.0f, 0.0f);
  c.target = vec3(0.0f);
  c.projection = Projection::Orthographic;
  c.ortho_height = 4.0f;
  scene.set_camera(c);
  for (const char* t : {"emission-absorption", "phong", "shadow-rays"}) {
    const Image image = render_with(scene, t);
    ASSERT_TRUE(all_finite(image)) << t;
  }
  const Image ea = render_with(scene, "emission-absorption");
  // Finite voxels 0..9 and 20..29: the NaN/inf cells and their neighbours'
  // interpolation (cells 9-10 and 19-20) are transparent, 18 voxels of 29 remain.
  EXPECT_NEAR(ea.at(8, 8).a, 1.0f - std::pow(0.9f, 18.0f), 0.01f);
}

TEST(EdgeCases, ATransparentVolumeShowsTheBackground) {
  Scene scene = lit(procedural_scene("spheres", ivec3(16), 16));
  scene.set_transfer_function(testing::step_tf(0.0f, vec3(1.0f), 0.0f));
  scene.set_background(vec3(0.2f, 0.3f, 0.4f));
  for (const char* t : {"emission-absorption", "phong", "shadow-rays"}) {
    const Image image = render_with(scene, t);
    for (const vec4& p : image.pixels()) ASSERT_EQ(vec3(p), vec3(0.2f, 0.3f, 0.4f)) << t;
  }
}

TEST(EdgeCases, ACameraInsideTheVolumeSeesFromWhereItIs) {
  Scene scene = lit(procedural_scene("marschner-lobb", ivec3(32), 24));
  scene.set_transfer_function(testing::step_tf(0.5f, vec3(0.8f), 0.2f));
  Camera c;
  c.eye = vec3(0.0f);
  c.target = vec3(0.0f, 10.0f, 0.0f);
  scene.set_camera(c);
  for (const char* t : {"emission-absorption", "phong", "shadow-rays"}) {
    const Image image = render_with(scene, t);
    ASSERT_TRUE(all_finite(image)) << t;
    EXPECT_GT(testing::mean_rgb(image, 0, 0, 24, 24).r, 0.01f) << t;
  }
}

TEST(EdgeCases, ALightAlongTheViewDirectionIsFine) {
  Scene scene = procedural_scene("spheres", ivec3(24), 24);
  scene.set_transfer_function(testing::step_tf(0.3f, vec3(0.8f), 0.5f));
  for (float sign : {1.0f, -1.0f}) {  // from behind the camera, and toward it
    Light l;
    l.direction = sign * glm::normalize(scene.camera().target - scene.camera().eye);
    scene.set_lights({l});
    for (const char* t : {"phong", "shadow-rays"}) {
      const Image image = render_with(scene, t);
      ASSERT_TRUE(all_finite(image)) << t;
    }
  }
}

TEST(EdgeCases, TimeStepsSelectTheFrame) {
  auto volume = std::make_shared<Volume>(ivec3(8), VoxelType::UInt8, 2);
  std::fill_n(volume->frame_as<std::uint8_t>(0), 512, std::uint8_t(0));
  std::fill_n(volume->frame_as<std::uint8_t>(1), 512, std::uint8_t(255));
  Scene scene = procedural_scene("slab", ivec3(8), 8);
  scene.set_volume(volume, 0);
  TransferFunction tf = testing::step_tf(0.5f, vec3(1.0f), 0.5f);
  tf.set_range(std::nullopt);  // "data": the range over all frames, so frame 0 stays empty
  scene.set_transfer_function(tf);
  const Image first = render_with(scene, "emission-absorption");
  scene.set_time_step(1);
  const Image second = render_with(scene, "emission-absorption");
  EXPECT_FLOAT_EQ(first.at(4, 4).a, 0.0f);
  EXPECT_GT(second.at(4, 4).a, 0.9f);
}

// Jitter trades banding for noise: a different image, but the same mean.
TEST(EdgeCases, JitterChangesPixelsButNotTheMean) {
  Scene scene = procedural_scene("spheres", ivec3(32), 32);
  scene.set_transfer_function(testing::step_tf(0.2f, vec3(1.0f), 0.3f));
  RenderSettings r = scene.render();
  r.step = 2.0f;  // coarse, so the offset matters
  scene.set_render(r);
  const Image plain = render_with(scene, "emission-absorption");
  r.jitter = true;
  scene.set_render(r);
  const Image jittered = render_with(scene, "emission-absorption");
  EXPECT_GT(rmse(plain, jittered), 1e-3);
  EXPECT_NEAR(testing::mean_rgb(plain, 0, 0, 32, 32).r, testing::mean_rgb(jittered, 0, 0, 32, 32).r, 0.01f);
}

// A camera so far away that t + step rounds back to t would march for ever.
TEST(EdgeCases, ACameraBeyondFloatMarchingRangeIsAnError) {
  Scene scene = lit(procedural_scene("spheres", ivec3(16), 8));
  Camera far = scene.camera();
  far.eye = vec3(0.0f, -1e12f, 0.0f);
  far.target = vec3(0.0f);
  scene.set_camera(far);
  try {
    (void)render_with(scene, "shadow-rays");
    ADD_FAILURE() << "a camera 1e12 away rendered";
  } catch (const InvalidScene& e) {
    EXPECT_EQ(e.key(), "camera.eye");
  }
  // Farther still, the distance to the target overflows a float by itself.
  for (const vec3& eye : {vec3(0.0f, -1e30f, 0.0f), vec3(3e38f, 0.0f, 0.0f)}) {
    far.eye = eye;
    far.target = -eye;
    EXPECT_THROW(scene.set_camera(far), InvalidScene);
  }
  // Far but marchable cameras still render.
  far.eye = vec3(0.0f, -2000.0f, 0.0f);
  far.target = vec3(0.0f);
  scene.set_camera(far);
  EXPECT_TRUE(all_finite(render_with(scene, "shadow-rays")));
}

}  // namespace
}  // namespace penumbra

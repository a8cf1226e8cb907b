#include "penumbra/base/error.h"
#include "penumbra/scene/camera.h"

#include <gtest/gtest.h>

#include <cmath>

namespace penumbra {
namespace {

TEST(Camera, CentralRayLooksAtTheTargetAndCornersSpanTheFov) {
  Camera c;
  c.eye = vec3(0.0f, -10.0f, 0.0f);
  c.target = vec3(0.0f);
  c.up = vec3(0.0f, 0.0f, 1.0f);
  c.fov_deg = 60.0f;
  const CameraView v = c.view();
  const Ray center = v.pixel_ray(50.0f, 50.0f, 100, 100);
  EXPECT_NEAR(center.direction.y, 1.0f, 1e-6f);
  // Top edge centre: 30 degrees above the axis; image y grows downward.
  const Ray top = v.pixel_ray(50.0f, 0.0f, 100, 100);
  EXPECT_NEAR(std::atan2(top.direction.z, top.direction.y), glm::radians(30.0f), 1e-5f);
  // +x is to the right of the image.
  EXPECT_GT(v.pixel_ray(99.0f, 50.0f, 100, 100).direction.x, 0.0f);
}

TEST(Camera, OrthographicRaysAreParallel) {
  Camera c;
  c.eye = vec3(0.0f, 0.0f, 10.0f);
  c.target = vec3(0.0f);
  c.up = vec3(0.0f, 1.0f, 0.0f);
  c.projection = Projection::Orthographic;
  c.ortho_height = 4.0f;
  const CameraView v = c.view();
  const Ray a = v.pixel_ray(0.0f, 0.0f, 64, 32);
  const Ray b = v.pixel_ray(64.0f, 32.0f, 64, 32);
  EXPECT_EQ(a.direction, b.direction);
  EXPECT_NEAR(a.origin.y, 2.0f, 1e-6f);   // top edge at half the height
  EXPECT_NEAR(a.origin.x, -4.0f, 1e-6f);  // aspect 2
}

TEST(Camera, OrbitKeepsTheDistanceAndTurnsAboutUp) {
  Camera c;
  c.eye = vec3(0.0f, -5.0f, 2.0f);
  c.target = vec3(1.0f, 0.0f, 0.0f);
  const float before = glm::distance(c.eye, c.target);
  c.orbit(90.0f, 0.0f);
  EXPECT_NEAR(glm::distance(c.eye, c.target), before, 1e-4f);
  EXPECT_NEAR(c.eye.z, 2.0f, 1e-4f);
  c.orbit(0.0f, 200.0f);  // clamped short of the pole
  EXPECT_NO_THROW(c.view());
}

TEST(Camera, FramingSeesTheWholeBox) {
  const Box3 box{vec3(-10.0f, -20.0f, -5.0f), vec3(30.0f, 20.0f, 5.0f)};
  const Camera c = Camera::framing(box);
  const CameraView v = c.view();
  for (int i = 0; i < 8; ++i) {
    const vec3 corner((i & 1) ? box.upper.x : box.lower.x, (i & 2) ? box.upper.y : box.lower.y,
                      (i & 4) ? box.upper.z : box.lower.z);
    const vec3 d = glm::normalize(corner - v.eye);
    const float angle = std::acos(glm::dot(d, v.forward));
    EXPECT_LT(angle, glm::radians(15.0f) + 1e-4f);  // inside the 30 degree cone
  }
}

TEST(Camera, DegenerateCamerasAreRejectedWithTheKey) {
  Camera c;
  c.eye = c.target;
  EXPECT_THROW(c.view(), InvalidScene);
  c = Camera{};
  c.up = glm::normalize(c.target - c.eye);
  try {
    c.view();
    FAIL();
  } catch (const InvalidScene& e) {
    EXPECT_EQ(e.key(), "camera.up");
  }
  c = Camera{};
  c.fov_deg = 180.0f;
  EXPECT_THROW(c.validate(), InvalidScene);
}

}  // namespace
}  // namespace penumbra

// The sweep plan against brute force: for light rays in world space, the
// pixel of a point nearer the light is never processed after the pixel of a
// point farther along the same light ray (the synchronisation IPSVI relies
// on), for point lights in front of and behind the camera, directional lights
// under perspective and orthographic cameras; zone weights cover every pixel
// once.
#include "penumbra/techniques/ipsvi/sweep_plan.h"

#include "penumbra/base/rng.h"

#include "test_scene.h"

#include <gtest/gtest.h>

#include <map>

namespace penumbra {
namespace {

constexpr int kPlanWidth = 64, kPlanHeight = 48;

CameraView camera(bool orthographic) {
  Camera c;
  c.eye = vec3(30.0f, -80.0f, 25.0f);
  c.target = vec3(0.0f);
  c.up = vec3(0.0f, 0.0f, 1.0f);
  c.fov_deg = 40.0f;
  c.projection = orthographic ? Projection::Orthographic : Projection::Perspective;
  c.ortho_height = 60.0f;
  return c.view();
}

// Pixel coordinates of a world point (false behind the camera).
bool to_pixel(const CameraView& c, vec3 p, vec2& pixel) {
  const vec3 q = p - c.eye;
  const float aspect = float(kPlanWidth) / float(kPlanHeight);
  float sx = glm::dot(q, c.right), sy = glm::dot(q, c.up);
  if (!c.orthographic) {
    const float z = glm::dot(q, c.forward);
    if (z <= 1e-3f) return false;
    sx /= z;
    sy /= z;
  }
  pixel = vec2((sx / (c.half_height * aspect) + 1.0f) * 0.5f * float(kPlanWidth),
               (1.0f - sy / c.half_height) * 0.5f * float(kPlanHeight));
  return pixel.x >= 0.0f && pixel.y >= 0.0f && pixel.x < float(kPlanWidth) && pixel.y < float(kPlanHeight);
}

// Per zone and pixel: the position of the pixel's line in the processing order.
std::vector<std::map<int, int>> line_order(const SweepPlan& plan) {
  std::vector<std::map<int, int>> order(plan.zones.size());
  for (std::size_t z = 0; z < plan.zones.size(); ++z) {
    const SweepZone& zone = plan.zones[z];
    for (std::size_t l = 0; l < zone.lines.size(); ++l) {
      for (int a = zone.lines[l].lo; a <= zone.lines[l].hi; ++a) {
        const int x = zone.axis == 0 ? zone.lines[l].coordinate : a;
        const int y = zone.axis == 0 ? a : zone.lines[l].coordinate;
        EXPECT_TRUE(order[z].emplace(x + kPlanWidth * y, int(l)).second) << "pixel twice in one zone";
      }
    }
  }
  return order;
}

// Walks many light rays through the region around the origin; counts the
// pairs checked.
int check_light_order(const CameraView& c, const Light& light, LightFlow expected_flow) {
  const ImageLight image_light = project_light(c, kPlanWidth, kPlanHeight, light);
  EXPECT_EQ(int(image_light.flow), int(expected_flow));
  const SweepPlan plan = make_sweep_plan(image_light, PixelRect{0, 0, kPlanWidth, kPlanHeight}, 5.0f);
  const auto order = line_order(plan);
  Pcg32 rng(7);
  int checked = 0;
  for (int i = 0; i < 4000; ++i) {
    const vec3 a = (vec3(rng.next_float(), rng.next_float(), rng.next_float()) - vec3(0.5f)) * 60.0f;
    const vec3 travel = light.at_infinity() ? light.direction : glm::normalize(a - light.position);
    const vec3 b = a + (0.5f + 6.0f * rng.next_float()) * travel;
    vec2 pa, pb;
    if (!to_pixel(c, a, pa) || !to_pixel(c, b, pb)) continue;
    const ivec2 ia(pa), ib(pb);
    for (std::size_t z = 0; z < plan.zones.size(); ++z) {
      const auto fa = order[z].find(ia.x + kPlanWidth * ia.y);
      const auto fb = order[z].find(ib.x + kPlanWidth * ib.y);
      if (fa == order[z].end() || fb == order[z].end()) continue;
      if (!(plan.zones[z].weight(vec2(ia) + 0.5f) > 0.0f && plan.zones[z].weight(vec2(ib) + 0.5f) > 0.0f)) continue;
      // Pixel rounding can put b's pixel one line before a's.
      EXPECT_LE(fa->second, fb->second + 1) << "zone " << z << ": pixel (" << ia.x << ", " << ia.y << ") after ("
                                            << ib.x << ", " << ib.y << ")";
      ++checked;
    }
  }
  return checked;
}


TEST(SweepPlan, PointLightInFrontOfTheCameraSweepsOutwardFromItsProjection) {
  const CameraView c = camera(false);
  const Light light = testing::point_light(vec3(-10.0f, 5.0f, 30.0f));
  const ImageLight il = project_light(c, kPlanWidth, kPlanHeight, light);
  vec2 expected;
  ASSERT_TRUE(to_pixel(c, light.position, expected));
  EXPECT_NEAR(il.position.x, expected.x, 1e-3f);
  EXPECT_NEAR(il.position.y, expected.y, 1e-3f);
  EXPECT_GT(check_light_order(c, light, LightFlow::Outward), 1000);
}

TEST(SweepPlan, PointLightBehindTheCameraSweepsInward) {
  const CameraView c = camera(false);
  EXPECT_GT(check_light_order(c, testing::point_light(c.eye - 40.0f * c.forward + vec3(5.0f, 0.0f, 10.0f)), LightFlow::Inward), 1000);
}

TEST(SweepPlan, DirectionalLightUnderPerspectiveSpreadsFromItsVanishingPoint) {
  const CameraView c = camera(false);
  // Travelling away from the camera: rays converge on the vanishing point.
  EXPECT_GT(check_light_order(c, testing::directional_light(c.forward + vec3(0.2f, 0.1f, -0.3f)), LightFlow::Inward), 1000);
  // Toward the camera: they spread out from it.
  EXPECT_GT(check_light_order(c, testing::directional_light(-c.forward + vec3(0.2f, 0.1f, -0.3f)), LightFlow::Outward), 1000);
  // Across the view: one parallel sweep.
  const Light across = testing::directional_light(c.right);
  EXPECT_GT(check_light_order(c, across, LightFlow::Parallel), 1000);
  const SweepPlan plan =
      make_sweep_plan(project_light(c, kPlanWidth, kPlanHeight, across), PixelRect{0, 0, kPlanWidth, kPlanHeight}, 5);
  ASSERT_EQ(plan.zones.size(), 1u);
  EXPECT_EQ(plan.zones[0].axis, 0);  // columns, swept left to right
  EXPECT_EQ(plan.zones[0].lines.front().coordinate, 0);
}

TEST(SweepPlan, OrthographicCameraSweepsParallelForDirectionalAndOutwardForPointLights) {
  const CameraView c = camera(true);
  EXPECT_GT(check_light_order(c, testing::directional_light(vec3(0.4f, 0.6f, -1.0f)), LightFlow::Parallel), 1000);
  EXPECT_GT(check_light_order(c, testing::point_light(vec3(10.0f, -20.0f, 35.0f)), LightFlow::Outward), 1000);
  // Along the view direction the image direction is undefined: the hint decides.
  const ImageLight along = project_light(c, kPlanWidth, kPlanHeight, testing::directional_light(c.forward));
  EXPECT_EQ(int(along.flow), int(LightFlow::Parallel));
  EXPECT_EQ(along.direction, vec2(0.0f));
  EXPECT_EQ(make_sweep_plan(along, PixelRect{0, 0, kPlanWidth, kPlanHeight}, 5.0f, 0).zones.at(0).axis, 0);
  EXPECT_EQ(make_sweep_plan(along, PixelRect{0, 0, kPlanWidth, kPlanHeight}, 5.0f, 1).zones.at(0).axis, 1);
}

TEST(SweepPlan, ZoneWeightsCoverEveryPixelOnceAndBlendOnlyNearTheDiagonals) {
  ImageLight il;
  il.flow = LightFlow::Outward;
  il.position = vec2(20.3f, 30.6f);
  const PixelRect rect{2, 3, kPlanWidth - 1, kPlanHeight - 2};
  const SweepPlan plan = make_sweep_plan(il, rect, 5.0f);
  EXPECT_EQ(plan.zones.size(), 4u);
  const auto order = line_order(plan);
  int blended = 0;
  for (int y = rect.y0; y < rect.y1; ++y) {
    for (int x = rect.x0; x < rect.x1; ++x) {
      const vec2 p = vec2(x, y) + 0.5f;
      float sum = 0.0f;
      int zones = 0;
      for (std::size_t z = 0; z < plan.zones.size(); ++z) {
        const float w = plan.zones[z].weight(p);
        if (w <= 0.0f) continue;
        EXPECT_TRUE(order[z].count(x + kPlanWidth * y)) << "pixel with weight missing from its zone's lines";
        sum += w;
        ++zones;
      }
      EXPECT_NEAR(sum, 1.0f, 1e-6f);
      if (zones > 1) {
        ++blended;
        const float angle = glm::degrees(std::atan2(std::abs(p.y - il.position.y), std::abs(p.x - il.position.x)));
        EXPECT_NEAR(angle, 45.0f, 5.0f);
      }
    }
  }
  EXPECT_GT(blended, 10);
  // Lines outside the rectangle are not planned.
  for (const SweepZone& zone : plan.zones) {
    for (const SweepLine& line : zone.lines) {
      EXPECT_GE(line.coordinate, zone.axis == 0 ? rect.x0 : rect.y0);
      EXPECT_LT(line.coordinate, zone.axis == 0 ? rect.x1 : rect.y1);
    }
  }
}

TEST(SweepPlan, ProjectedBoxRectBoundsTheBoxAndFallsBackToTheImage) {
  const CameraView c = camera(false);
  const Box3 box{vec3(-5.0f), vec3(5.0f)};
  const PixelRect r = projected_box_rect(c, kPlanWidth, kPlanHeight, box);
  EXPECT_FALSE(r.empty());
  EXPECT_LT(r.x1 - r.x0, kPlanWidth);
  for (int i = 0; i < 8; ++i) {
    vec2 p;
    const vec3 corner(i & 1 ? 5.0f : -5.0f, i & 2 ? 5.0f : -5.0f, i & 4 ? 5.0f : -5.0f);
    ASSERT_TRUE(to_pixel(c, corner, p));
    EXPECT_GE(p.x, float(r.x0));
    EXPECT_LE(p.x, float(r.x1));
    EXPECT_GE(p.y, float(r.y0));
    EXPECT_LE(p.y, float(r.y1));
  }
  const Box3 around_eye{c.eye - vec3(1.0f), c.eye + vec3(1.0f)};
  const PixelRect all = projected_box_rect(c, kPlanWidth, kPlanHeight, around_eye);
  EXPECT_EQ(all.x1 - all.x0, kPlanWidth);
  EXPECT_EQ(all.y1 - all.y0, kPlanHeight);
}

}  // namespace
}  // namespace penumbra

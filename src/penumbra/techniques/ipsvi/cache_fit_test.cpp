// The cache fitted to the camera (section 5.2): everything the camera sees of
// the box, and every visible floor point whose light ray crosses the box,
// lands inside the cache; zooming in keeps the cache's size bounded, and its
// texels about a pixel wide across the light. A trimmed grid (the automatic
// cache of ipsvi) covers the same with fewer texels where the fitted
// rectangle is long.
#include "penumbra/techniques/ipsvi/cache_fit.h"

#include "test_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace penumbra {
namespace {

const Box3 kFitBox{vec3(-20.0f, -15.0f, -10.0f), vec3(20.0f, 15.0f, 10.0f)};
constexpr int kFitWidth = 96, kFitHeight = 64;

// Independent of the frustum planes of cache_fit.cpp: the point's image
// coordinates.
bool seen(const CameraView& c, vec3 p) {
  const vec3 q = p - c.eye;
  const float z = glm::dot(q, c.forward);
  if (!(z > 0.0f)) return false;
  const float aspect = float(kFitWidth) / float(kFitHeight);
  const float x = glm::dot(q, c.right) / (z * c.half_height * aspect), y = glm::dot(q, c.up) / (z * c.half_height);
  return glm::abs(x) <= 1.0f && glm::abs(y) <= 1.0f;
}

bool inside_cache(const LightCacheProjection& p, vec3 point) {
  const vec3 q = p.project(point);
  return q.x >= 0.0f && q.y >= 0.0f && q.x <= float(p.size) && q.y <= float(p.rows);
}

Camera zoomed(float fov_deg) {
  Camera camera = Camera::framing(kFitBox, vec3(0.6f, -1.0f, 0.45f), vec3(0.0f, 0.0f, 1.0f), 32.0f);
  camera.fov_deg = fov_deg;
  camera.target = vec3(8.0f, -3.0f, 2.0f);  // zoom toward a point off the centre
  return camera;
}


TEST(CacheFit, CoversWhatTheCameraSeesAndKeepsItsSizeWhenZooming) {
  int trimmed_at_3 = 0;
  for (const Light& light : {testing::directional_light(vec3(1.0f, 0.2f, -0.3f)), testing::directional_light(vec3(0.3f, -0.5f, -1.0f)),
                             testing::point_light(vec3(60.0f, -80.0f, 50.0f))}) {
    for (const bool trim : {false, true}) {
      int size_at_9 = 0;
      for (const float fov : {32.0f, 9.0f, 3.0f}) {
        const CameraView view = zoomed(fov).view();
        const LightCacheRegion region = visible_cache_region(view, kFitWidth, kFitHeight, kFitBox, nullptr, 0);
        const LightCacheProjection p = fit_light_cache_projection(light, kFitBox, region, 0, 2 * kFitWidth, trim);
        const LightCacheProjection square = fit_light_cache_projection(light, kFitBox, region, 0, 2 * kFitWidth);
        ASSERT_EQ(std::max(p.size, p.rows), square.size);
        if (!trim) {
          ASSERT_EQ(p.rows, p.size);
        } else if (fov == 3.0f && p.size * p.rows < square.size * square.size) {
          ++trimmed_at_3;
        }
        int seen_points = 0;
        for (int i = 0; i < 40 * 40 * 40; ++i) {
          const vec3 f((float(i % 40) + 0.5f) / 40.0f, (float(i / 40 % 40) + 0.5f) / 40.0f, (float(i / 1600) + 0.5f) / 40.0f);
          const vec3 x = kFitBox.lower + f * kFitBox.extent();
          if (!seen(view, x)) continue;
          ++seen_points;
          ASSERT_TRUE(inside_cache(p, x)) << "fov " << fov << ", point " << x.x << " " << x.y << " " << x.z;
        }
        EXPECT_GT(seen_points, 20);
        const int side = std::max(p.size, p.rows);
        if (fov == 9.0f) size_at_9 = side;
        std::printf("fov %4.1f%s: cache %d x %d, texel %.3f x %.3f, pixel %.3f\n", fov, trim ? ", trimmed" : "", p.size,
                    p.rows, p.texel_world_size(50.0f).x, p.texel_world_size(50.0f).y, region.pixel);
        // Over the whole box the cache would grow 3x per side from fov 9 to 3.
        EXPECT_LE(side, 2 * kFitWidth) << "fov " << fov;
        if (fov == 3.0f) {
          EXPECT_LE(side, int(1.6f * float(size_at_9)));
        }
        if (light.at_infinity() && fov < 32.0f) {
          // Across the light the texels follow the pixel (up to the 2^(1/4) snap).
          EXPECT_LE(p.texel_world_size(0.0f).y, 1.2f * region.pixel) << "fov " << fov;
        }
      }
    }
  }
  // Zoomed in, the rectangles are long: trimming saves texels for some light.
  EXPECT_GT(trimmed_at_3, 0);
}

// With a texel budget (ipsvi's automatic cache: 1.4 texels per image pixel;
// here 1.5)
// the cache keeps its size from a wide view down to fov 3, still covers all
// the camera sees, and keeps pixel-wide texels where they fit the budget.
// Without the budget the same fits grow several times from fov 32 to 3.
TEST(CacheFit, ATexelBudgetBoundsTheCacheAtEveryZoom) {
  const double budget = 1.5 * kFitWidth * kFitHeight;
  int over_without = 0;
  for (const Light& light : {testing::directional_light(vec3(1.0f, 0.2f, -0.3f)), testing::directional_light(vec3(0.3f, -0.5f, -1.0f)),
                             testing::point_light(vec3(60.0f, -80.0f, 50.0f))}) {
    double unbounded_at_32 = 0.0;
    for (const float fov : {40.0f, 32.0f, 16.0f, 9.0f, 6.0f, 3.0f}) {
      const CameraView view = zoomed(fov).view();
      LightCacheRegion region = visible_cache_region(view, kFitWidth, kFitHeight, kFitBox, nullptr, 0);
      const LightCacheProjection unbounded = fit_light_cache_projection(light, kFitBox, region, 0, 3 * kFitWidth, true);
      region.max_texels = budget;
      const LightCacheProjection p = fit_light_cache_projection(light, kFitBox, region, 0, 3 * kFitWidth, true);
      const double texels = double(p.size) * p.rows, unbounded_texels = double(unbounded.size) * unbounded.rows;
      std::printf("fov %4.1f: %d x %d (%.2f per pixel), without the budget %d x %d (%.2f)\n", fov, p.size, p.rows,
                  texels / (kFitWidth * kFitHeight), unbounded.size, unbounded.rows,
                  unbounded_texels / (kFitWidth * kFitHeight));
      EXPECT_LE(texels, budget) << "fov " << fov;
      if (unbounded_texels <= budget) {
        EXPECT_EQ(p.size, unbounded.size) << "fov " << fov;  // under the budget nothing changes
        EXPECT_EQ(p.rows, unbounded.rows) << "fov " << fov;
      } else {
        // Coarser only as far as the budget asks: one step finer would not fit.
        EXPECT_GT(texels, 0.6 * budget) << "fov " << fov;
      }
      if (fov == 32.0f) unbounded_at_32 = unbounded_texels;
      if (fov < 32.0f && unbounded_texels > 2.0 * unbounded_at_32) ++over_without;
      for (int i = 0; i < 40 * 40 * 40; ++i) {
        const vec3 f((float(i % 40) + 0.5f) / 40.0f, (float(i / 40 % 40) + 0.5f) / 40.0f, (float(i / 1600) + 0.5f) / 40.0f);
        const vec3 x = kFitBox.lower + f * kFitBox.extent();
        if (!seen(view, x)) continue;
        ASSERT_TRUE(inside_cache(p, x)) << "fov " << fov << ", point " << x.x << " " << x.y << " " << x.z;
      }
    }
  }
  EXPECT_GT(over_without, 3);  // the budget is what bounds these fits
}

// A floor below the box, lit at a slant: floor points in view whose light
// ray crosses the box (they may lie in its shadow) are covered even where
// that crossing is off screen.
TEST(CacheFit, CoversVisibleFloorPointsShadowedFromOffScreen) {
  const Plane floor{vec3(0.0f, 0.0f, -12.0f), vec3(0.0f, 0.0f, 1.0f), vec3(0.8f)};
  Camera camera = zoomed(12.0f);
  camera.target = vec3(-30.0f, -10.0f, -12.0f);  // the floor beside the box
  const CameraView view = camera.view();
  const Light light = testing::directional_light(vec3(-1.0f, -0.2f, -0.6f));
  const LightCacheRegion region = visible_cache_region(view, kFitWidth, kFitHeight, kFitBox, &floor, 1);
  const LightCacheProjection p = fit_light_cache_projection(light, kFitBox, region, 0, 2 * kFitWidth);
  int shadowed = 0;
  for (int i = 0; i < 200 * 200; ++i) {
    const vec3 x(-120.0f + 1.2f * float(i % 200), -120.0f + 1.2f * float(i / 200), -12.0f);
    if (!seen(view, x)) continue;
    if (intersect_box(Ray{x, -light.direction}, kFitBox, 0.0f, kInfinity).empty()) continue;
    ++shadowed;
    ASSERT_TRUE(inside_cache(p, x)) << x.x << " " << x.y;
  }
  EXPECT_GT(shadowed, 20);
  const LightCacheRegion without = visible_cache_region(view, kFitWidth, kFitHeight, kFitBox, nullptr, 0);
  EXPECT_LT(without.points.size() + 1, region.points.size() + region.plane_points.size());
}

// A light inside the box gets an octahedral map. Where the light lies outside
// what the camera sees of the box, the map holds only the directions toward
// that, turned so that they lie about its centre: every visible point of the
// box lands inside, on a texel whose light ray points at it, and zoomed in the
// map is a small part of the sphere (the visible floor's points are left to
// their own light rays, plane_light in ipsvi_ray.h). Where the light lies in
// view every direction is needed: the whole map, within its own budget.
TEST(CacheFit, AnOctahedralMapHoldsTheDirectionsTowardWhatTheCameraSees) {
  const Plane floor{vec3(0.0f, 0.0f, -12.0f), vec3(0.0f, 0.0f, 1.0f), vec3(0.8f)};
  const double map_budget = 4.0 * kFitWidth * kFitHeight;
  int parts_at_3 = 0;
  for (const vec3& position : {vec3(-15.0f, 10.0f, 5.0f), vec3(0.0f, 0.0f, 0.0f), vec3(8.5f, -3.5f, 2.0f)}) {
    const Light light = testing::point_light(position);
    for (const float fov : {32.0f, 9.0f, 3.0f}) {
      const CameraView view = zoomed(fov).view();
      LightCacheRegion region = visible_cache_region(view, kFitWidth, kFitHeight, kFitBox, &floor, 1);
      region.max_texels = 1.4 * kFitWidth * kFitHeight;  // for frustum maps only
      region.max_map_texels = map_budget;
      const LightCacheProjection p = fit_light_cache_projection(light, kFitBox, region, 0, 3 * kFitWidth, true);
      ASSERT_EQ(p.mapping, LightMapping::Octahedral);
      const bool whole = p.lower == vec2(0.0f) && p.scale.x == float(p.size) && p.size == p.rows;
      const bool in_view = seen(view, position);
      std::printf("light (%g, %g, %g)%s, fov %4.1f: %s %d x %d, %.0f texels across the sphere\n", position.x,
                  position.y, position.z, in_view ? " in view" : "", fov, whole ? "whole map" : "part", p.size,
                  p.rows, double(p.scale.x));
      const double texels = double(p.size) * double(p.rows);
      // (A part's rectangle is aligned to whole texels: a row and a column more.)
      EXPECT_LE(texels, map_budget + (whole ? 0.0 : double(p.size + p.rows + 1))) << "fov " << fov;
      EXPECT_EQ(whole, in_view) << "fov " << fov;
      if (fov == 3.0f && !whole) {
        ++parts_at_3;
        // Finer texels than the whole map's in the same budget.
        EXPECT_GT(double(p.scale.x), 1.25 * std::sqrt(map_budget)) << "zoomed in, a part of the sphere";
      }
      int seen_points = 0;
      auto check = [&](vec3 x) {
        const vec3 q = p.project(x);
        ASSERT_TRUE(inside_cache(p, x)) << "fov " << fov << ", point " << x.x << " " << x.y << " " << x.z;
        const vec3 along = p.texel_ray(vec2(q)).direction;
        ASSERT_GT(glm::dot(along, glm::normalize(x - position)), 0.99999f) << "fov " << fov;
        ++seen_points;
      };
      for (int i = 0; i < 40 * 40 * 40; ++i) {
        const vec3 f((float(i % 40) + 0.5f) / 40.0f, (float(i / 40 % 40) + 0.5f) / 40.0f, (float(i / 1600) + 0.5f) / 40.0f);
        const vec3 x = kFitBox.lower + f * kFitBox.extent();
        if (seen(view, x)) check(x);
      }
      EXPECT_GT(seen_points, 20);
    }
  }
  EXPECT_EQ(parts_at_3, 2);  // the two lights out of view
}

}  // namespace
}  // namespace penumbra

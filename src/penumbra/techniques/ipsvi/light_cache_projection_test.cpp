// The light-space projection of the illumination cache: round trips between
// texels and light rays, coverage of the volume box, and the choice of mapping.
#include "penumbra/techniques/ipsvi/light_cache_projection.h"

#include "penumbra/base/error.h"

#include "test_scene.h"

#include <gtest/gtest.h>

namespace penumbra {
namespace {

const Box3 kBox{vec3(-20.0f, -15.0f, -10.0f), vec3(20.0f, 15.0f, 10.0f)};


void expect_round_trip(const LightCacheProjection& p) {
  for (vec2 uv : {vec2(3.5f, 7.25f), vec2(0.5f * float(p.size)), vec2(float(p.size) - 2.0f, 1.5f)}) {
    for (float depth : {5.0f, 17.0f}) {
      const Ray r = p.texel_ray(uv);
      const vec3 q = p.project(r.at(depth));
      EXPECT_NEAR(q.x, uv.x, 1e-3f);
      EXPECT_NEAR(q.y, uv.y, 1e-3f);
      EXPECT_NEAR(q.z, depth, 1e-3f);
    }
  }
}

// Every point of the box lands inside the cache with a depth in [0, max_depth]:
// the cache covers everything a sample can be.
void expect_box_covered(const LightCacheProjection& p) {
  for (int i = 0; i < 27; ++i) {
    const vec3 f(float(i % 3) * 0.5f, float(i / 3 % 3) * 0.5f, float(i / 9) * 0.5f);
    const vec3 q = p.project(kBox.lower + f * kBox.extent());
    EXPECT_GE(q.x, 0.0f);
    EXPECT_GE(q.y, 0.0f);
    EXPECT_LE(q.x, float(p.size));
    EXPECT_LE(q.y, float(p.size));
    EXPECT_GE(q.z, -1e-3f);
    EXPECT_LE(q.z, p.max_depth + 1e-3f);
  }
}

TEST(LightCacheProjection, DirectionalIsOrthographicAlongTheLight) {
  const Light light = testing::directional_light(vec3(0.3f, -0.5f, -1.0f));
  const LightCacheProjection p = make_light_cache_projection(light, kBox, 64);
  EXPECT_EQ(p.mapping, LightMapping::Orthographic);
  expect_round_trip(p);
  expect_box_covered(p);
  // Depth grows along the light by the distance travelled.
  const vec3 a = p.project(vec3(1.0f, 2.0f, 3.0f));
  const vec3 b = p.project(vec3(1.0f, 2.0f, 3.0f) + 7.0f * light.direction);
  EXPECT_NEAR(b.z - a.z, 7.0f, 1e-4f);
  EXPECT_NEAR(b.x, a.x, 1e-4f);
  EXPECT_NEAR(b.y, a.y, 1e-4f);
  // The square fits the box footprint: texels are as small as they can be.
  EXPECT_NEAR(p.texel_world_size(0.0f).x, 1.0f / p.scale.x, 1e-6f);
  EXPECT_EQ(p.scale.x, p.scale.y) << "square texels over the whole box";
}

TEST(LightCacheProjection, PointOutsideIsAFrustumAndInsideAnOctahedralMap) {
  const LightCacheProjection far = make_light_cache_projection(testing::point_light(vec3(10.0f, -90.0f, 60.0f)), kBox, 64);
  EXPECT_EQ(far.mapping, LightMapping::Perspective);
  expect_round_trip(far);
  expect_box_covered(far);
  EXPECT_NEAR(far.project(vec3(10.0f, -90.0f, 60.0f) + vec3(3.0f, 4.0f, 0.0f)).z, 5.0f, 1e-4f);

  const LightCacheProjection inside = make_light_cache_projection(testing::point_light(vec3(1.0f, 2.0f, 3.0f)), kBox, 64);
  EXPECT_EQ(inside.mapping, LightMapping::Octahedral);
  expect_round_trip(inside);
  expect_box_covered(inside);
  // A light right beside a face would need a frustum wider than ~145 degrees.
  EXPECT_EQ(make_light_cache_projection(testing::point_light(vec3(0.0f, 0.0f, 11.0f)), kBox, 64).mapping, LightMapping::Octahedral);
}

TEST(LightCacheProjection, OctahedralMapRoundTripsEveryOctant) {
  for (int i = 0; i < 8; ++i) {
    const vec3 d = glm::normalize(vec3(i & 1 ? 0.3f : -0.6f, i & 2 ? 0.8f : -0.2f, i & 4 ? 0.5f : -0.9f));
    const vec3 back = LightCacheProjection::octahedral_decode(LightCacheProjection::octahedral_encode(d));
    EXPECT_NEAR(glm::length(back - d), 0.0f, 1e-5f);
  }
}

TEST(LightCacheProjection, BadSizeNamesTheParameter) {
  try {
    make_light_cache_projection(testing::directional_light(vec3(0.0f, 0.0f, -1.0f)), kBox, 0);
    FAIL() << "no error";
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.name(), "cache_size");
  }
}

}  // namespace
}  // namespace penumbra

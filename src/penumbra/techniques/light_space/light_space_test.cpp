// Light-space projections (orthographic, perspective, cube map), map storage
// and the light-ray march against analytic answers.
#include "penumbra/base/error.h"
#include "penumbra/base/memory_budget.h"
#include "penumbra/base/rng.h"
#include "penumbra/render/scene_resources.h"
#include "penumbra/techniques/light_space/light_map.h"
#include "penumbra/techniques/light_space/light_ray.h"
#include "test_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <type_traits>

namespace penumbra {
namespace {

// A std::vector of maps (one per light or mesh) moves them when it grows
// instead of copying them.
static_assert(std::is_nothrow_move_constructible_v<LightMap>);
static_assert(std::is_nothrow_move_assignable_v<LightMap>);

const Box3 kBox{vec3(-20.0f, -15.0f, -10.0f), vec3(20.0f, 15.0f, 10.0f)};

vec3 random_point(Pcg32& rng, const Box3& box) {
  return box.lower + vec3(rng.next_float(), rng.next_float(), rng.next_float()) * box.extent();
}

// Every point of the box falls inside the window, and a texel ray at a
// depth locates back to the same texel coordinates and depth.
void expect_covers_box_and_round_trips(const LightProjection& p) {
  Pcg32 rng(7);
  const float n = float(p.resolution);
  for (int i = 0; i < 500; ++i) {
    const vec3 q = random_point(rng, kBox);
    LightMapPoint m;
    ASSERT_TRUE(p.locate(q, m));
    EXPECT_GE(m.texel.x, 0.0f);
    EXPECT_GE(m.texel.y, 0.0f);
    EXPECT_LE(m.texel.x, n);
    EXPECT_LE(m.texel.y, n);
    EXPECT_GE(m.depth, 0.0f);
    // Back through the texel ray: the same point.
    const Ray ray = p.texel_ray(m.face, m.texel);
    const vec3 back = ray.at(m.depth);
    EXPECT_NEAR(glm::length(back - q), 0.0f, 1e-3f * glm::length(kBox.extent()));
  }
}

TEST(LightProjection, DirectionalLightIsOrthographicAndFitsTheBox) {
  Light light;
  light.direction = glm::normalize(vec3(0.3f, -0.5f, -1.0f));
  const LightProjection p = make_light_projection(light, kBox, 256);
  EXPECT_EQ(p.kind, LightProjectionKind::Orthographic);
  EXPECT_EQ(p.face_count, 1);
  expect_covers_box_and_round_trips(p);
  // Texel rays are parallel to the light.
  const Ray a = p.texel_ray(0, vec2(3.5f, 100.5f));
  EXPECT_NEAR(glm::dot(a.direction, light.direction), 1.0f, 1e-6f);
  // Tight fit: the window is at most a few texels wider than the box's
  // projection (the half diagonal bounds it).
  EXPECT_LE(p.window_half, 0.5f * glm::length(kBox.extent()) * 1.02f);
}

TEST(LightProjection, PointLightOutsideIsOnePerspectiveFrustum) {
  Light light;
  light.type = LightType::Point;
  light.position = vec3(30.0f, -60.0f, 50.0f);
  const LightProjection p = make_light_projection(light, kBox, 512);
  EXPECT_EQ(p.kind, LightProjectionKind::Perspective);
  EXPECT_EQ(p.face_count, 1);
  expect_covers_box_and_round_trips(p);
  // Depth is the distance from the light.
  LightMapPoint m;
  ASSERT_TRUE(p.locate(vec3(0.0f), m));
  EXPECT_NEAR(m.depth, glm::length(light.position), 1e-3f);
  // A point behind the light cannot be seen by the map: lit.
  EXPECT_FALSE(p.locate(light.position + (light.position - kBox.center()), m));
}

TEST(LightProjection, PointLightInsideOrCloseGetsACubeMap) {
  for (vec3 position : {vec3(0.0f), vec3(5.0f, -3.0f, 2.0f), vec3(21.0f, 0.0f, 0.0f)}) {
    Light light;
    light.type = LightType::Point;
    light.position = position;
    const LightProjection p = make_light_projection(light, kBox, 64);
    EXPECT_EQ(p.face_count, 6);
    EXPECT_EQ(p.resolution, 32);  // half per face
    expect_covers_box_and_round_trips(p);
    // Every direction falls on the face of its major axis, inside [0, n]^2.
    Pcg32 rng(11);
    for (int i = 0; i < 200; ++i) {
      const vec3 d = glm::normalize(vec3(rng.next_float(), rng.next_float(), rng.next_float()) - 0.5f);
      LightMapPoint m;
      ASSERT_TRUE(p.locate(position + 3.0f * d, m));
      const vec3 w = p.faces[m.face].w;
      EXPECT_GE(glm::dot(d, w), max_component(glm::abs(d)) - 1e-6f);
      EXPECT_NEAR(m.depth, 3.0f, 1e-4f);
      EXPECT_GE(m.texel.x, 0.0f);
      EXPECT_LE(m.texel.x, float(p.resolution));
    }
  }
}

TEST(LightProjection, EnvironmentLightsHaveNoMap) {
  Light light;
  light.type = LightType::Environment;
  const LightProjection p = make_light_projection(light, kBox, 256);
  EXPECT_EQ(p.kind, LightProjectionKind::None);
  EXPECT_EQ(p.texel_count(), 0);
  LightMapPoint m;
  EXPECT_FALSE(p.locate(vec3(0.0f), m));
}

TEST(LightMap, LayoutOutsideLookupsAndBudget) {
  Light light;
  const LightProjection p = make_light_projection(light, kBox, 256);
  LightMap map("test map", p, 3);
  EXPECT_EQ(map.bytes(), 256u * 256u * 3u * sizeof(float));
  map.fill([](const Ray&, std::int64_t index, float* texel) {
    texel[0] = float(index);
    texel[1] = texel[2] = 0.0f;
  });
  const LightMapView v = map.view();
  EXPECT_EQ(v.texel(0, 5, 7)[0], float(7 * 256 + 5));
  EXPECT_EQ(v.texel(0, -1, 7), nullptr);  // outside a single-face map: no texel (lit)
  EXPECT_EQ(v.texel(0, 5, 256), nullptr);

  Light point;
  point.type = LightType::Point;
  const LightProjection cube = make_light_projection(point, kBox, 256);
  LightMap cube_map("test cube", cube, 1);
  EXPECT_EQ(cube_map.bytes(), 6u * 128u * 128u * sizeof(float));
  EXPECT_EQ(cube_map.view().texel(2, -3, 300), cube_map.view().texel(2, 0, 127));  // cube faces clamp

  const std::uint64_t budget = memory_budget_bytes();
  set_memory_budget_bytes(1u << 20);
  EXPECT_THROW(LightMap("big map", make_light_projection(light, kBox, 4096), 12), OutOfMemoryBudget);
  set_memory_budget_bytes(budget);
}

// Through the homogeneous slab the light ray's segments cover the chord and
// their opacities multiply to exp(-sigma d): the grey transmittance.
TEST(LightRay, SlabSegmentsComposeTheChordTransmittance) {
  Scene scene = testing::procedural_scene("slab", ivec3(20, 16, 12));
  scene.set_transfer_function(testing::step_tf(0.0f, vec3(0.25f, 0.5f, 1.0f), 0.1f));
  SceneResources resources;
  resources.update(scene);
  const RenderView v = resources.view(scene);
  const float sigma = -std::log(0.9f);
  Light light;
  light.direction = glm::normalize(vec3(0.4f, 0.2f, -1.0f));
  const LightProjection p = make_light_projection(light, v.box, 256);
  Pcg32 rng(5);
  for (int i = 0; i < 50; ++i) {
    const Ray ray = p.texel_ray(0, vec2(40.0f + 170.0f * rng.next_float(), 40.0f + 170.0f * rng.next_float()));
    const Interval chord = intersect_box(ray, v.box, 0.0f, kInfinity);
    float covered = 0.0f;
    vec3 grey(1.0f), colored(1.0f), chromatic(1.0f), unsaturated(1.0f), saturated(1.0f);
    float previous_end = chord.t0;
    with_sampler(v.volume, [&](const auto& sampler) {
      march_light_ray(v, sampler, ray, kInfinity, [&](const LightSegment& s) {
        EXPECT_NEAR(s.start, previous_end, 1e-3f);
        previous_end = s.start + s.length;
        covered += s.length;
        grey *= 1.0f - stop_probability(s, ShadowColorModel{ShadowColor::Grey});
        colored *= 1.0f - stop_probability(s, ShadowColorModel{ShadowColor::Paper});
        chromatic *= 1.0f - stop_probability(s, ShadowColorModel{ShadowColor::Chromatic, 1.0f});
        unsaturated *= 1.0f - stop_probability(s, ShadowColorModel{ShadowColor::Chromatic, 0.0f});
        saturated *= 1.0f - stop_probability(s, ShadowColorModel{ShadowColor::Chromatic, kMaxShadowSaturation});
        return true;
      });
      return 0;
    });
    EXPECT_NEAR(covered, chord.length(), 1e-3f);
    EXPECT_NEAR(grey.r, std::exp(-sigma * chord.length()), 1e-4f);
    EXPECT_EQ(grey.r, grey.b);
    // Paper colours: each segment stops alpha (1 - t); blue (t = 1) passes freely.
    EXPECT_EQ(colored.b, 1.0f);
    EXPECT_GT(colored.g, grey.g);
    EXPECT_LT(colored.r, colored.g);
    // Chromatic: c = t / max t = (0.25, 0.5, 1), mean 7/12, extinction
    // weights k = 1 + (mean - c) = (4/3, 13/12, 7/12): they average 1, so the
    // product of the channels is the grey transmittance cubed.
    const vec3 k(4.0f / 3.0f, 13.0f / 12.0f, 7.0f / 12.0f);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(chromatic[c], std::exp(-k[c] * sigma * chord.length()), 1e-4f);
    EXPECT_NEAR(chromatic.r * chromatic.g * chromatic.b, grey.r * grey.g * grey.b, 1e-4f);
    // Saturation 0 is grey; the largest keeps every k >= 0 (blue: 1 - 1.5 * 5/12 = 3/8) and the product.
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(unsaturated[c], grey[c], 1e-5f);
    EXPECT_NEAR(saturated.b, std::exp(-0.375f * sigma * chord.length()), 1e-4f);
    EXPECT_NEAR(saturated.r * saturated.g * saturated.b, grey.r * grey.g * grey.b, 1e-4f);
  }
}

}  // namespace
}  // namespace penumbra

// shadow-map kernels: the stored depth against the analytic threshold depth
// of a homogeneous slab, binary lookups, PCF fractions.
#include "penumbra/base/rng.h"
#include "penumbra/render/scene_resources.h"
#include "penumbra/techniques/shadow_map/shadow_map_kernels.h"
#include "test_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

namespace penumbra {
namespace {

// Through the slab, transmittance is exp(-sigma d) from the entry, so the
// accumulated opacity passes the threshold at d = -ln(1 - threshold) / sigma.
// The stored depth interpolates inside the crossing segment, so it matches
// to float rounding plus the linear-versus-exponential difference inside one
// half-voxel segment (< 0.02 voxel here).
TEST(ShadowMap, DepthIsWhereTheAccumulatedOpacityPassesTheThreshold) {
  Scene scene = testing::procedural_scene("slab", ivec3(24, 24, 40));
  scene.set_transfer_function(testing::step_tf(0.0f, vec3(1.0f), 0.1f));
  SceneResources resources;
  resources.update(scene);
  const RenderView v = resources.view(scene);
  const float sigma = -std::log(0.9f);
  Light light;
  light.direction = vec3(0.0f, 0.0f, -1.0f);
  const LightProjection p = make_light_projection(light, v.box, 256);
  for (float threshold : {0.1f, 0.5f, 0.9f}) {
    const LightMap map = build_shadow_map(v, p, threshold);
    for (int x : {64, 128, 190}) {
      const Ray ray = p.texel_ray(0, vec2(float(x) + 0.5f, 128.5f));
      const float entry = intersect_box(ray, v.box, 0.0f, kInfinity).t0;
      const float expected = -std::log(1.0f - threshold) / sigma;
      EXPECT_NEAR(map.view().texel(0, x, 128)[0] - entry, expected, 0.02f) << "threshold " << threshold;
    }
  }
  // A threshold the slab never reaches: no occluder depth.
  scene.set_transfer_function(testing::step_tf(0.0f, vec3(1.0f), 0.001f));
  resources.update(scene);
  const LightMap thin = build_shadow_map(resources.view(scene), p, 0.5f);
  EXPECT_EQ(thin.view().texel(0, 128, 128)[0], kInfinity);
}

// The lookup is a binary test; PCF averages (2r+1)^2 of them, giving
// multiples of 1/(2r+1)^2 and fractional values along shadow edges.
TEST(ShadowMap, LookupsAreBinaryAndPcfGivesFractions) {
  Scene scene = testing::procedural_scene("spheres", ivec3(32));
  scene.set_transfer_function(testing::step_tf(0.3f, vec3(1.0f), 0.6f));
  SceneResources resources;
  resources.update(scene);
  const RenderView v = resources.view(scene);
  Light light;
  light.direction = glm::normalize(vec3(0.3f, 0.2f, -1.0f));
  const LightMap map = build_shadow_map(v, make_light_projection(light, v.box, 256), 0.5f);
  const LightMapView view = map.view();
  const LightSample ls = sample_light(light, vec3(0.0f));
  const ShadowMapVisibility binary{&view, 0, 0.0f};
  const ShadowMapVisibility pcf3x3{&view, 1, 0.0f};
  Pcg32 rng(1);
  std::set<float> plain_values, pcf_values;
  for (int i = 0; i < 3000; ++i) {
    const vec3 q = v.box.lower + vec3(rng.next_float(), rng.next_float(), rng.next_float()) * v.box.extent();
    plain_values.insert(binary(0, q, ls).r);
    const vec3 pcf = pcf3x3(0, q, ls);
    EXPECT_EQ(pcf.r, pcf.g);
    const float nine = pcf.r * 9.0f;
    EXPECT_NEAR(nine, std::round(nine), 1e-5f);
    pcf_values.insert(pcf.r);
  }
  EXPECT_EQ(plain_values, (std::set<float>{0.0f, 1.0f}));
  EXPECT_GT(pcf_values.size(), 4u) << "PCF should give fractional visibility near shadow edges";
  // Outside the map's window nothing lies toward the light: lit.
  EXPECT_EQ(binary(0, v.box.upper + vec3(100.0f, 0.0f, 0.0f), ls).r, 1.0f);
}

// A bias moves the test's depth toward the light: with a huge one everything
// is lit, with none the far side of an occluder is dark.
TEST(ShadowMap, DepthBiasLightsWhatLiesWithinIt) {
  Scene scene = testing::procedural_scene("slab", ivec3(16));
  scene.set_transfer_function(testing::step_tf(0.0f, vec3(1.0f), 0.5f));
  SceneResources resources;
  resources.update(scene);
  const RenderView v = resources.view(scene);
  Light light;
  const LightMap map = build_shadow_map(v, make_light_projection(light, v.box, 256), 0.5f);
  const LightMapView view = map.view();
  const LightSample ls = sample_light(light, vec3(0.0f));
  const vec3 bottom(0.0f, 0.0f, v.box.lower.z + 0.5f);
  const ShadowMapVisibility unbiased{&view, 0, 0.0f};
  const ShadowMapVisibility biased{&view, 0, 20.0f};
  EXPECT_EQ(unbiased(0, bottom, ls).r, 0.0f);
  EXPECT_EQ(biased(0, bottom, ls).r, 1.0f);
}

}  // namespace
}  // namespace penumbra

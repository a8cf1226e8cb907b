// deep-shadow-map on a real light ray: its nodes against the brute-force
// transmittance of the same ray (reference_transmittance.h), and its
// lookups against shadow-ray marching.
#include "penumbra/base/rng.h"
#include "penumbra/render/scene_resources.h"
#include "penumbra/techniques/deep_shadow_map/deep_shadow_map_kernels.h"
#include "penumbra/techniques/light_space/reference_transmittance.h"
#include "test_scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <vector>

namespace penumbra {
namespace {

const ShadowColorModel kColors{};  // the default: chromatic, saturation 1

// Translucent coloured spheres with opaque cores: smooth and sharp changes.
Scene coloured_spheres() {
  Scene scene = testing::procedural_scene("spheres", ivec3(32));
  TransferFunction tf({{0.0f, vec3(1.0f), 0.0f},
                       {0.2f, vec3(0.9f, 0.4f, 0.2f), 0.0f},
                       {0.3f, vec3(0.9f, 0.4f, 0.2f), 0.15f},
                       {0.7f, vec3(0.2f, 0.6f, 0.9f), 0.3f},
                       {1.0f, vec3(0.5f), 0.95f}});
  tf.set_range(vec2(0.0f, 1.0f));
  scene.set_transfer_function(tf);
  return scene;
}

Light slanted_light() {
  Light light;
  light.direction = glm::normalize(vec3(0.4f, 0.3f, -1.0f));
  return light;
}

// With the tolerance bound each texel reports, the stored function is within
// it of the brute-force transmittance of the texel's ray at every depth (up
// to the 1e-4 floor below which a ray counts as dark).
TEST(DeepShadowMap, ErrorIsBoundedByTheCompressionTolerance) {
  const Scene scene = coloured_spheres();
  SceneResources resources;
  resources.update(scene);
  const RenderView v = resources.view(scene);
  const LightProjection p = make_light_projection(slanted_light(), v.box, 256);
  for (int nodes : {3, 8}) {
    int at_base = 0, texels = 0;
    float worst = 0.0f;
    for (int y = 8; y < 256; y += 16) {
      for (int x = 8; x < 256; x += 16) {
        const Ray ray = p.texel_ray(0, vec2(float(x) + 0.5f, float(y) + 0.5f));
        std::vector<float> texel(4 * nodes);
        const float bound = with_sampler(v.volume, [&](const auto& sampler) {
          return deep_shadow_texel(v, sampler, ray, kColors, 0.01f, nodes, texel.data());
        });
        ASSERT_LT(bound, kInfinity) << "the largest level should fit these rays";
        const Interval chord = volume_interval(v, ray, 0.0f, kInfinity);
        if (chord.empty()) continue;
        ++texels;
        at_base += bound == 0.01f;
        for (float z = chord.t0 - 1.0f; z < chord.t1 + 1.0f; z += 0.1f) {
          const vec3 error =
              glm::abs(evaluate_deep_shadow(texel.data(), nodes, z) - reference_transmittance(v, ray, z, kColors));
          worst = std::max(worst, max_component(error) - bound);
          ASSERT_LE(max_component(error), bound + 2e-4f) << "texel " << x << ", " << y << " depth " << z;
        }
      }
    }
    std::printf("[deep-shadow-map] %d nodes: %d of %d texels at the base tolerance, worst excess %.2e\n", nodes,
                at_base, texels, worst);
    EXPECT_GT(texels, 100);
    // With 8 nodes nearly every ray meets the base tolerance; with 3 many do.
    EXPECT_GT(at_base, nodes == 8 ? texels * 9 / 10 : texels / 3) << nodes << " nodes";
  }
}

// More nodes: the lookups converge to the transmittance of the light ray
// (the brute-force function of the nearest texel's ray).
TEST(DeepShadowMap, ConvergesToTheRayMarchedTransmittanceWithMoreNodes) {
  const Scene scene = coloured_spheres();
  SceneResources resources;
  resources.update(scene);
  const RenderView v = resources.view(scene);
  const Light light = slanted_light();
  const LightProjection p = make_light_projection(light, v.box, 256);
  Pcg32 rng(9);
  std::vector<vec3> points;
  for (int i = 0; i < 400; ++i)
    points.push_back(v.box.lower + vec3(rng.next_float(), rng.next_float(), rng.next_float()) * v.box.extent());
  float previous = kInfinity;
  for (int nodes : {2, 3, 6, 16}) {
    const LightMap map = build_deep_shadow_map(v, p, nodes, 0.002f, kColors);
    const LightMapView view = map.view();
    const DeepShadowVisibility visibility{&view, nodes, false, 0.0f};  // no bias: the texel's own function
    double sum = 0.0;
    float worst = 0.0f;
    for (const vec3& q : points) {
      LightMapPoint m;
      ASSERT_TRUE(p.locate(q, m));
      const Ray ray = p.texel_ray(0, glm::floor(m.texel) + 0.5f);
      const vec3 expected = reference_transmittance(v, ray, m.depth, kColors);
      const float error = max_component(glm::abs(visibility(0, q, sample_light(light, q)) - expected));
      sum += error;
      worst = std::max(worst, error);
    }
    const float mean = float(sum / double(points.size()));
    std::printf("[deep-shadow-map] %d nodes: error mean %.5f, worst %.5f\n", nodes, mean, worst);
    EXPECT_LE(mean, previous + 1e-4f) << nodes << " nodes";
    previous = mean;
    if (nodes == 16) {
      EXPECT_LT(worst, 0.005f);
    }
  }
}

// Grey (colored = false) and with bilinear lookups, the deep shadow map
// approximates what shadow-rays marches from the sample toward the light.
// The two march different sample grids (light-aligned versus from the
// sample) and the map interpolates between texel rays, so they differ by
// discretisation: within 0.03 at 512^2 and 16 nodes.
TEST(DeepShadowMap, GreyLookupsMatchShadowRays) {
  const Scene scene = coloured_spheres();
  SceneResources resources;
  resources.update(scene);
  const RenderView v = resources.view(scene);
  const Light light = slanted_light();
  const LightMap map = build_deep_shadow_map(v, make_light_projection(light, v.box, 512), 16, 0.002f,
                                             ShadowColorModel{ShadowColor::Grey});
  const LightMapView view = map.view();
  const DeepShadowVisibility visibility{&view, 16, true};
  Pcg32 rng(4);
  double sum = 0.0;
  for (int i = 0; i < 400; ++i) {
    const vec3 q = v.box.lower + vec3(rng.next_float(), rng.next_float(), rng.next_float()) * v.box.extent();
    const LightSample ls = sample_light(light, q);
    RayStats stats;
    const float expected = march_transmittance(v, Ray{q, ls.to_light}, ls.distance, 1.0f, stats);
    const vec3 got = visibility(0, q, ls);
    EXPECT_EQ(got.r, got.b);
    EXPECT_NEAR(got.r, expected, 0.03f);
    sum += std::abs(got.r - expected);
  }
  std::printf("[deep-shadow-map] grey vs shadow-rays: mean error %.5f\n", sum / 400.0);
  EXPECT_LT(sum / 400.0, 0.005);
}

}  // namespace
}  // namespace penumbra

// shadow-rays' light_samples: soft shadows of area lights against the
// analytic penumbra of a sharp edge, the packet path against the scalar path,
// and the shadow cache holding area means.
//
// The penumbra model (tests/support/penumbra_edge.h): a straight edge a
// distance d above a floor perpendicular to the light's central direction.
//   distant, uniform: angle_deg = theta is the cone's HALF-angle (light.h), so
//     the light seen through the edge is a disk of radius R = d tan(theta) on
//     the floor (to first order in theta: the cone is uniform in solid angle,
//     not on the plane; error ~ theta^2, 1 % at 6 degrees). The fraction of
//     it on the lit side of a line at signed offset s = u R is the circular
//     segment (acos(-u) + u sqrt(1 - u^2)) / pi; 90 % at u = 0.68705, so the
//     0-100 % width is 2 d tan(theta) and the 10-90 % width
//     2 * 0.68705 * d tan(theta) = 1.37410 d tan(theta).
//   distant, gaussian: angle_deg = sigma; the offsets on the virtual light
//     plane are exactly N(0, tan(sigma)^2) per axis (light_sampling.h), so
//     the visibility is the normal CDF of s / (d tan(sigma)) and the 10-90 %
//     width 2 * 1.28155 * d tan(sigma) = 2.56310 d tan(sigma).
//   sphere or disk of radius r at height H above the edge: by similar
//     triangles the disk of radius R = r d / H on the floor, the same
//     circular segment: 1.37410 r d / H (the sphere's silhouette seen from
//     the floor has radius r (1 - O((r / (H + d))^2)), 0.3 % here).
// Tolerance 2 %: the measured errors are 0.0-0.5 % (64 samples per floor
// point, 64 rows averaged, 0.5-unit pixels, the occluder's 2-voxel
// thickness and trilinear edge; the sphere's is the largest).
#include "penumbra/analysis/image_metrics.h"
#include "penumbra/backends/cpu/packets.h"
#include "penumbra/base/error.h"
#include "penumbra/render/scene_resources.h"
#include "penumbra/techniques/registry.h"
#include "penumbra/techniques/shadow_rays/shadow_cache.h"
#include "penumbra_edge.h"
#include "test_scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace penumbra {
namespace {

using testing::edge_scene;
using testing::penumbra_width_10_90;
using testing::render_with;

constexpr float kCircularSegment1090 = 1.37410f;  // 2 u, (acos(-u) + u sqrt(1 - u^2)) / pi = 0.9
constexpr float kGaussian1090 = 2.56310f;         // 2 * Phi^-1(0.9)
constexpr float kTolerance = 0.02f;

float measured_width(const testing::EdgeScene& edge, int light_samples, float expected = 0.0f) {
  const Image image = render_with(edge.scene, "shadow-rays", {{"light_samples", double(light_samples)}});
  const float width = penumbra_width_10_90(edge, image, testing::unshadowed_floor(edge));
  testing::save_test_image(image, "shadow-rays-edge-" + std::to_string(int(edge.scene.lights()[0].type)) + "-" +
                                      std::to_string(light_samples) + ".png");
  if (expected > 0.0f) {
    std::printf("[shadow-rays edge] %d samples: 10-90 width %.3f, model %.3f (%+.1f %%)\n", light_samples, width,
                expected, 100.0 * (width / expected - 1.0));
  }
  return width;
}

Light distant(float angle_deg, LightProfile profile) { return testing::distant_light(angle_deg, profile); }

TEST(ShadowRaysArea, UniformDistantLightPenumbraMatchesTheCircularSegment) {
  const float theta = 6.0f, d = 60.0f;
  const testing::EdgeScene edge = edge_scene(distant(theta, LightProfile::Uniform), d);
  const float expected = kCircularSegment1090 * d * std::tan(glm::radians(theta));
  EXPECT_NEAR(measured_width(edge, 64, expected), expected, kTolerance * expected);
  // The default (one ray to the centre) keeps today's hard shadow: the edge's
  // own width, about a voxel.
  EXPECT_LT(measured_width(edge, 1), 1.5f);
}

TEST(ShadowRaysArea, GaussianDistantLightPenumbraMatchesTheNormalCdf) {
  const float sigma = 3.0f, d = 60.0f;
  const testing::EdgeScene edge = edge_scene(distant(sigma, LightProfile::Gaussian), d);
  const float expected = kGaussian1090 * d * std::tan(glm::radians(sigma));
  EXPECT_NEAR(measured_width(edge, 64, expected), expected, kTolerance * expected);
}

TEST(ShadowRaysArea, SphereAndDiskLightPenumbraFollowsSimilarTriangles) {
  const float r = 20.0f, height = 200.0f, d = 60.0f;
  const float expected = kCircularSegment1090 * r * d / height;
  for (LightType type : {LightType::Sphere, LightType::Disk}) {
    SCOPED_TRACE(type == LightType::Sphere ? "sphere" : "disk");
    Light light;
    light.type = type;
    light.radius = r;
    light.intensity = (height + d) * (height + d);  // about unit radiance on the floor
    const testing::EdgeScene edge = edge_scene(light, d, 64, 32.0f, height);
    EXPECT_NEAR(measured_width(edge, 64, expected), expected, kTolerance * expected);
  }
}

// The same lanes-generic kernel serves the scalar and packet paths: the same
// image, samples on the volume (packets) and on a floor (scalar plane hits).
TEST(ShadowRaysArea, PacketPathMatchesScalarPath) {
  SimdMode packets;
  try {
    packets = parse_simd_mode("avx2");
  } catch (const InvalidArgument&) {
    GTEST_SKIP() << "this CPU or build has no SIMD target";
  }
  Scene scene = testing::with_floor(testing::lit_spheres(32));
  Light sphere;
  sphere.type = LightType::Sphere;
  sphere.position = vec3(30.0f, -30.0f, 60.0f);
  sphere.radius = 12.0f;
  sphere.intensity = 4000.0f;
  Light cone = distant(5.0f, LightProfile::Uniform);
  cone.direction = scene.lights()[0].direction;
  scene.set_lights({cone, sphere});
  const SimdMode saved = simd_mode();
  set_simd_mode(SimdMode::Off);
  const Image scalar = render_with(scene, "shadow-rays", {{"light_samples", 8.0}});
  set_simd_mode(packets);
  RenderStats stats;
  const Image packet = render_with(scene, "shadow-rays", {{"light_samples", 8.0}}, &stats);
  set_simd_mode(saved);
  EXPECT_NE(stats.simd, SimdTarget::Scalar) << "the packet path ran";
  EXPECT_LE(rmse(packet, scalar), 1e-4);
  // And the samples soften: the image differs from the centre-ray one.
  EXPECT_GT(rmse(scalar, render_with(scene, "shadow-rays")), 1e-3);
}

// Each cache texel holds the area mean of the same rays the uncached path
// marches, and the technique reads that cache when both are on.
TEST(ShadowRaysArea, CacheHoldsTheAreaMean) {
  Scene scene = testing::lit_spheres(24);
  scene.set_transfer_function(testing::step_tf(0.3f, vec3(1.0f), 0.6f));
  Light cone = distant(10.0f, LightProfile::Uniform);
  cone.direction = scene.lights()[0].direction;
  scene.set_lights({cone});
  SceneResources resources;
  resources.update(scene);
  const RenderView v = resources.shadow_view(scene);
  const Volume soft = build_shadow_cache(v, 0, 1.0f, 16, 0.25f);
  const Volume hard = build_shadow_cache(v, 0, 1.0f, 1, 0.25f);
  const ivec3 dims = soft.dims();
  const float* soft_texels = soft.frame_as<float>(0);
  const float* hard_texels = hard.frame_as<float>(0);
  const VolumeView view = soft.view();
  double worst = 0.0, softening = 0.0;
  for (int z = 0; z < dims.z; ++z) {
    for (int y = 0; y < dims.y; ++y) {
      for (int x = 0; x < dims.x; ++x) {
        const std::size_t i = std::size_t(x + dims.x * (y + dims.y * z));
        RayStats stats;
        const float expected = light_transmittance(v, view.world_from_index(vec3(x, y, z)), 0, 1.0f, 16, stats);
        worst = std::max(worst, double(std::abs(soft_texels[i] - expected)));
        softening = std::max(softening, double(std::abs(soft_texels[i] - hard_texels[i])));
      }
    }
  }
  EXPECT_LT(worst, 1e-6);
  EXPECT_GT(softening, 0.05);
  const ParameterSettings cached{{"shadow_cache", true}, {"cache_resolution", 0.25}};
  ParameterSettings cached_area = cached;
  cached_area["light_samples"] = 16.0;
  EXPECT_GT(rmse(render_with(scene, "shadow-rays", cached_area), render_with(scene, "shadow-rays", cached)), 1e-3);
}

TEST(ShadowRaysArea, LightSamplesOutOfRangeNameTheParameter) {
  const Scene scene = testing::lit_spheres(8);
  try {
    render_with(scene, "shadow-rays", {{"light_samples", 0.0}});
    FAIL() << "light_samples = 0 was accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("light_samples"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace penumbra

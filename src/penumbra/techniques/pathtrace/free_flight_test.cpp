// Delta and ratio tracking against exp(-tau): analytic for the homogeneous
// slab, and for a heterogeneous medium tau integrated by brute force (a very
// fine midpoint rule over the same trilinear field and TF table, with no
// macrocells), so the majorant grid and the cell walk are what is tested.
#include "penumbra/render/scene_resources.h"
#include "penumbra/techniques/pathtrace/free_flight.h"
#include "test_scene.h"

#include <gtest/gtest.h>

#include <cmath>

namespace penumbra {
namespace {

using testing::procedural_scene;
using testing::step_tf;

// tau along the ray up to t_max by the midpoint rule with `steps` steps over
// the clipped interval.
double brute_force_optical_depth(const RenderView& v, const Ray& ray, float t_max, int steps) {
  const Interval iv = volume_interval(v, ray, 0.0f, t_max);
  if (iv.empty()) return 0.0;
  const double dt = double(iv.t1 - iv.t0) / steps;
  double tau = 0.0;
  for (int i = 0; i < steps; ++i) {
    const float t = float(iv.t0 + (i + 0.5) * dt);
    tau += double(v.tf.lookup(v.volume.sample(ray.at(t))).a) * dt;
  }
  return tau;
}

struct TrackingMeans {
  double delta = 0.0;  // fraction of delta-tracking flights that got through
  double ratio = 0.0;  // mean ratio-tracking estimate
};

TrackingMeans run_trackers(const RenderView& v, const Ray& ray, float t_max, int trials, std::uint64_t& lookups) {
  TrackingMeans m;
  with_sampler(v.volume, [&](const auto& sampler) {
    for (int i = 0; i < trials; ++i) {
      Pcg32 rng(std::uint64_t(i) * 7919u + 1u);
      const Interval iv = volume_interval(v, ray, 0.0f, t_max);
      Collision c;
      m.delta += delta_tracking(v, sampler, ray, iv.t0, iv.t1, rng, c, lookups) ? 0.0 : 1.0;
      m.ratio += ratio_tracking(v, sampler, ray, t_max, rng, lookups);
    }
    return 0;
  });
  m.delta /= trials;
  m.ratio /= trials;
  return m;
}

TEST(FreeFlight, HomogeneousSlabTransmittanceIsExpOfSigmaTimesLength) {
  Scene scene = procedural_scene("slab", ivec3(16));
  const float alpha = 0.1f;
  scene.set_transfer_function(step_tf(0.5f, vec3(1.0f), alpha));
  SceneResources resources;
  resources.update(scene);
  const RenderView v = resources.view(scene);
  const float sigma = -std::log(1.0f - alpha);  // unit_length = spacing 1
  const int trials = 20000;
  // Through the whole box (15 units), and stopping inside it at a point light.
  for (const auto& [ray, t_max] : {std::pair{Ray{vec3(-30.0f, 0.3f, 0.2f), vec3(1.0f, 0.0f, 0.0f)}, kInfinity},
                                   std::pair{Ray{vec3(-30.0f, 0.3f, 0.2f), vec3(1.0f, 0.0f, 0.0f)}, 26.0f}}) {
    const double expected = std::exp(-sigma * volume_interval(v, ray, 0.0f, t_max).length());
    std::uint64_t lookups = 0;
    const TrackingMeans m = run_trackers(v, ray, t_max, trials, lookups);
    // Both estimators are Bernoulli here (the majorant equals sigma_t), so the
    // standard error of the mean is sqrt(T (1 - T) / n) ~ 0.0035; 4 of them.
    const double tolerance = 4.0 * std::sqrt(expected * (1.0 - expected) / trials);
    EXPECT_NEAR(m.delta, expected, tolerance);
    EXPECT_NEAR(m.ratio, expected, tolerance);
  }
}

TEST(FreeFlight, HeterogeneousTransmittanceMatchesBruteForceOpticalDepth) {
  Scene scene = procedural_scene("spheres", ivec3(32));
  // A ramp, so sigma_t varies inside every macrocell and majorants are loose.
  TransferFunction tf({{0.0f, vec3(1.0f), 0.0f}, {0.1f, vec3(1.0f), 0.0f}, {1.0f, vec3(1.0f), 0.25f}});
  tf.set_range(vec2(0.0f, 1.0f));
  scene.set_transfer_function(tf);
  scene.set_clip_planes({vec4(0.2f, 0.1f, 1.0f, 6.0f)});
  SceneResources resources;
  resources.update(scene);
  const RenderView v = resources.view(scene);
  // Through the spheres (centres in world units: (-5.4, -3.1, 0.8) r 5.9,
  // (5.9, 1.9, 1.6) r 5.0, (0, 7.0, -5.4) r 4.0).
  const Ray rays[] = {
      {vec3(-40.0f, -3.1f, 0.8f), glm::normalize(vec3(1.0f, 0.02f, 0.0f))},
      {vec3(5.9f, -40.0f, 1.5f), glm::normalize(vec3(0.0f, 1.0f, 0.01f))},
      {vec3(30.0f, 7.0f, 20.0f), glm::normalize(vec3(-30.0f, 0.0f, -25.4f))},
      {vec3(-5.4f, -3.1f, 0.8f), glm::normalize(vec3(0.3f, 0.4f, -1.0f))},  // from inside, cut by the clip plane
  };
  const int trials = 8000;
  int in_range = 0;
  for (const Ray& ray : rays) {
    const double expected = std::exp(-brute_force_optical_depth(v, ray, kInfinity, 20000));
    std::uint64_t lookups = 0;
    const TrackingMeans m = run_trackers(v, ray, kInfinity, trials, lookups);
    SCOPED_TRACE(::testing::Message() << "expected T = " << expected);
    // Delta tracking is Bernoulli (sd sqrt(T (1 - T))); ratio tracking's
    // per-flight sd is at most that, and Russian roulette adds at most
    // 0.1 * sqrt(T). 4 standard errors of the mean plus 0.005 for the
    // brute-force quadrature.
    const double sd = std::sqrt(expected * (1.0 - expected)) + 0.1 * std::sqrt(expected);
    const double tolerance = 4.0 * sd / std::sqrt(double(trials)) + 0.005;
    EXPECT_NEAR(m.delta, expected, tolerance);
    EXPECT_NEAR(m.ratio, expected, tolerance);
    in_range += expected > 0.1 && expected < 0.9;
  }
  EXPECT_GE(in_range, 3) << "the rays must see partial transmittance for the test to mean anything";
}

TEST(FreeFlight, EmptySpaceCostsNoLookups) {
  Scene scene = procedural_scene("spheres", ivec3(32));
  scene.set_transfer_function(step_tf(0.3f, vec3(1.0f), 0.5f));
  SceneResources resources;
  resources.update(scene);
  const RenderView v = resources.view(scene);
  // Along an edge of the box, far from every sphere: all macrocells are empty.
  const Ray ray{vec3(-20.0f, -15.4f, 15.4f), vec3(1.0f, 0.0f, 0.0f)};
  std::uint64_t lookups = 0;
  const TrackingMeans m = run_trackers(v, ray, kInfinity, 100, lookups);
  EXPECT_EQ(m.delta, 1.0);
  EXPECT_EQ(m.ratio, 1.0);
  EXPECT_EQ(lookups, 0u);
}

}  // namespace
}  // namespace penumbra

// cssm: the stochastic estimate is unbiased against the brute-force coloured
// transmittance, generation is deterministic per seed, offsets follow the
// paper and scale with the resolution.
#include "penumbra/render/scene_resources.h"
#include "penumbra/techniques/cssm/cssm_kernels.h"
#include "penumbra/techniques/light_space/reference_transmittance.h"
#include "test_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <algorithm>
#include <vector>

namespace penumbra {
namespace {

Scene coloured_spheres() {
  Scene scene = testing::procedural_scene("spheres", ivec3(24));
  TransferFunction tf({{0.0f, vec3(1.0f), 0.0f},
                       {0.2f, vec3(0.9f, 0.4f, 0.2f), 0.0f},
                       {0.3f, vec3(0.9f, 0.4f, 0.2f), 0.2f},
                       {1.0f, vec3(0.2f, 0.6f, 0.9f), 0.5f}});
  tf.set_range(vec2(0.0f, 1.0f));
  scene.set_transfer_function(tf);
  return scene;
}

// Averaged over seeds, the shadow factor at a sample equals the coloured
// transmittance (brute force, reference_transmittance.h) averaged over the
// texels its 13 offsets read, per channel, within 4.5 standard errors (the
// error measured from the spread over the seeds).
TEST(Cssm, VisibilityIsUnbiasedPerChannel) {
  const Scene scene = coloured_spheres();
  SceneResources resources;
  resources.update(scene);
  const RenderView v = resources.view(scene);
  Light light;
  light.direction = glm::normalize(vec3(0.3f, 0.5f, -1.0f));
  const int n = 40;  // a small map keeps 300 generations fast
  const LightProjection p = make_light_projection(light, v.box, n);
  Pcg32 rng(17);
  std::vector<vec3> points;
  for (int i = 0; i < 40; ++i)
    points.push_back(v.box.lower + vec3(rng.next_float(), rng.next_float(), rng.next_float()) * v.box.extent());
  const int seeds = 300;
  std::vector<dvec3> sum(points.size(), dvec3(0.0)), sum_sq(points.size(), dvec3(0.0));
  for (int seed = 0; seed < seeds; ++seed) {
    const LightMap map = build_cssm(v, p, std::uint32_t(seed), 0, true);
    const LightMapView view = map.view();
    // Offsets at their paper size in texels of this small map.
    const CssmVisibility visibility = make_cssm_visibility(&view, 13, kCssmOffsetResolution / float(n));
    for (std::size_t i = 0; i < points.size(); ++i) {
      const dvec3 f(visibility(0, points[i], sample_light(light, points[i])));
      sum[i] += f;
      sum_sq[i] += f * f;
    }
  }
  int partial = 0;
  double worst_z = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    LightMapPoint m;
    ASSERT_TRUE(p.locate(points[i], m));
    vec3 expected(0.0f);
    for (int j = 0; j < 13; ++j) {
      const vec2 t = glm::floor(m.texel + vec2(float(kCssmOffsets[j][0]), float(kCssmOffsets[j][1])));
      const bool inside = t.x >= 0.0f && t.y >= 0.0f && t.x < float(n) && t.y < float(n);
      expected += inside ? reference_transmittance(v, p.texel_ray(0, t + 0.5f), m.depth, true) : vec3(1.0f);
    }
    expected /= 13.0f;
    const dvec3 mean = sum[i] / double(seeds);
    const dvec3 variance = glm::max(sum_sq[i] / double(seeds) - mean * mean, dvec3(0.0));
    for (int c = 0; c < 3; ++c) {
      const double standard_error = std::sqrt(variance[c] / double(seeds));
      EXPECT_NEAR(mean[c], expected[c], 4.5 * standard_error + 1e-3) << "point " << i << " channel " << c;
      if (standard_error > 0) worst_z = std::max(worst_z, std::abs(mean[c] - expected[c]) / standard_error);
      partial += expected[c] > 0.05f && expected[c] < 0.95f;
    }
  }
  std::printf("[cssm] unbiased: worst |mean - expected| = %.2f standard errors; %d partly lit channels\n", worst_z,
              partial);
  EXPECT_GT(partial, 20) << "the test should probe partly shadowed samples";
}

TEST(Cssm, GenerationIsDeterministicPerSeed) {
  const Scene scene = coloured_spheres();
  SceneResources resources;
  resources.update(scene);
  const RenderView v = resources.view(scene);
  Light light;
  const LightProjection p = make_light_projection(light, v.box, 64);
  const LightMap a = build_cssm(v, p, 5, 0, true);
  const LightMap b = build_cssm(v, p, 5, 0, true);
  const LightMap c = build_cssm(v, p, 6, 0, true);
  const LightMap other_light = build_cssm(v, p, 5, 1, true);
  int differ_seed = 0, differ_light = 0, stopped = 0;
  for (std::int64_t i = 0; i < p.texel_count(); ++i) {
    for (int ch = 0; ch < 3; ++ch) {
      ASSERT_EQ(a.texel(i)[ch], b.texel(i)[ch]);
      differ_seed += a.texel(i)[ch] != c.texel(i)[ch];
      differ_light += a.texel(i)[ch] != other_light.texel(i)[ch];
      stopped += a.texel(i)[ch] < kInfinity;
    }
  }
  EXPECT_GT(stopped, 300);
  EXPECT_GT(differ_seed, stopped / 2);
  EXPECT_GT(differ_light, stopped / 2);
}

// A black opaque wall stops every channel in its first segment, at one
// depth shared by the channels; a blue wall lets the blue photons through.
TEST(Cssm, ChannelsStopWhereTheirColourIsAbsorbed) {
  Scene scene = testing::procedural_scene("slab", ivec3(16));
  scene.set_transfer_function(testing::step_tf(0.0f, vec3(0.0f), 1.0f));
  SceneResources resources;
  resources.update(scene);
  Light light;
  const LightProjection p = make_light_projection(light, resources.view(scene).box, 64);
  const LightMap black = build_cssm(resources.view(scene), p, 1, 0, true);
  const float entry = intersect_box(p.texel_ray(0, vec2(32.5f)), resources.view(scene).box, 0.0f, kInfinity).t0;
  const float* texel = black.view().texel(0, 32, 32);
  EXPECT_EQ(texel[0], texel[1]);
  EXPECT_EQ(texel[1], texel[2]);
  EXPECT_GE(texel[0], entry);
  EXPECT_LE(texel[0], entry + resources.view(scene).step);

  scene.set_transfer_function(testing::step_tf(0.0f, vec3(0.0f, 0.0f, 1.0f), 0.5f));
  resources.update(scene);
  const LightMap blue = build_cssm(resources.view(scene), p, 1, 0, true);
  int blue_through = 0, red_stopped = 0;
  for (std::int64_t i = 0; i < p.texel_count(); ++i) {
    blue_through += blue.texel(i)[2] == kInfinity;
    red_stopped += blue.texel(i)[0] < kInfinity;
  }
  EXPECT_EQ(blue_through, p.texel_count());
  EXPECT_GT(red_stopped, p.texel_count() * 3 / 4);  // the window's margin texels miss the box
}

TEST(Cssm, OffsetsFollowThePaperAndScaleWithResolution) {
  LightMapView map;
  map.projection.resolution = 1024;
  for (int count : {7, 13, 21}) {
    const CssmVisibility v = make_cssm_visibility(&map, count, 1.0f);
    EXPECT_EQ(v.offset_count, count);
    EXPECT_EQ(v.offset(map, 0), vec2(0.0f));
    vec2 sum(0.0f);
    for (int j = 0; j < count; ++j) sum += v.offset(map, j);
    if (count != 7) {
      EXPECT_EQ(sum, vec2(0.0f)) << "the 13 and 21 sets are symmetric";
    }
  }
  const CssmVisibility paper = make_cssm_visibility(&map, 13, 1.0f);
  const vec2 expected[13] = {{0, 0}, {3, 3}, {-3, 3}, {3, -3}, {-3, -3}, {4, 0}, {-4, 0},
                             {0, 4}, {0, -4}, {7, 0}, {-7, 0}, {0, 7}, {0, -7}};
  for (int j = 0; j < 13; ++j) EXPECT_EQ(paper.offset(map, j), expected[j]);
  LightMapView fine = map;
  fine.projection.resolution = 2048;
  EXPECT_EQ(paper.offset(fine, 12), vec2(0.0f, -14.0f));
  fine.projection.resolution = 4096;
  EXPECT_EQ(make_cssm_visibility(&fine, 13, 0.5f).offset(fine, 9), vec2(14.0f, 0.0f));
}

}  // namespace
}  // namespace penumbra

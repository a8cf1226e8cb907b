// cssm: the stochastic estimate is unbiased against the brute-force coloured
// transmittance (with the depth-aware filter and the paper's), generation
// is deterministic per seed, the entry depths match brute force, offsets
// follow the paper in texels of the map.
#include "penumbra/render/scene_resources.h"
#include "penumbra/techniques/cssm/cssm_kernels.h"
#include "penumbra/techniques/light_space/reference_transmittance.h"
#include "test_scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace penumbra {
namespace {

Scene cssm_spheres() {
  Scene scene = testing::procedural_scene("spheres", ivec3(24));
  TransferFunction tf({{0.0f, vec3(1.0f), 0.0f},
                       {0.2f, vec3(0.9f, 0.4f, 0.2f), 0.0f},
                       {0.3f, vec3(0.9f, 0.4f, 0.2f), 0.2f},
                       {1.0f, vec3(0.2f, 0.6f, 0.9f), 0.5f}});
  tf.set_range(vec2(0.0f, 1.0f));
  scene.set_transfer_function(tf);
  return scene;
}

struct UnbiasedCase {
  const char* name;
  ShadowColorModel colors;
  bool depth_aware;
};

// Averaged over seeds, the shadow factor at a sample equals the brute-force
// transmittance (reference_transmittance.h) of the rays of the taps the
// filter keeps, at the depths it reads them, averaged, per channel. The
// kept taps and depths come from the map's entry depths, which are not
// random (checked against brute force too). 80 points with partly lit
// channels and 600 seeds: each channel within 4.5 standard errors, and
// over all partly lit channels the mean squared z-score near 1 and the
// mean z-score near 0, which a 5 % error in the stop probability or a
// staircase depth (a fixed point of the stopping segment) push out.
TEST(Cssm, VisibilityIsUnbiasedPerChannel) {
  const Scene scene = cssm_spheres();
  SceneResources resources;
  resources.update(scene);
  const RenderView v = resources.view(scene);
  Light light;
  light.direction = glm::normalize(vec3(0.3f, 0.5f, -1.0f));
  const int n = 40;  // a small map keeps 600 generations fast
  const LightProjection p = make_light_projection(light, v.box, n);
  const UnbiasedCase cases[] = {{"chromatic, depth-aware", ShadowColorModel{}, true},
                                {"paper colours, paper filter", ShadowColorModel{ShadowColor::Paper}, false}};
  for (const UnbiasedCase& c : cases) {
    SCOPED_TRACE(c.name);
    const LightMap first = build_cssm(v, p, 0, 0, c.colors);
    const LightMapView first_view = first.view();
    const CssmVisibility plan = make_cssm_visibility(&first_view, 13, 1.0f, c.depth_aware);
    // The expected value per point from the taps the filter keeps.
    Pcg32 rng(17);
    std::vector<vec3> points, expected;
    int entries_checked = 0;
    for (int tries = 0; tries < 2000 && points.size() < 80; ++tries) {
      const vec3 q = v.box.lower + vec3(rng.next_float(), rng.next_float(), rng.next_float()) * v.box.extent();
      LightMapPointL<ScalarLanes> m;
      ASSERT_TRUE(p.locate<ScalarLanes>(q, m));
      CssmVisibility::Plane<ScalarLanes> plane{0.0f, 0.0f};
      if (c.depth_aware) plane = plan.entry_plane<ScalarLanes>(first_view, m);
      vec3 sum(0.0f);
      int kept = 0;
      for (int j = 0; j < 13; ++j) {
        const auto tap = plan.tap<ScalarLanes>(first_view, m, plane, j);
        if (!tap.kept) continue;
        ++kept;
        const vec2 t = glm::floor(vec2(m.x, m.y) + plan.offset(first_view, j));
        if (!tap.inside) {
          sum += vec3(1.0f);
          continue;
        }
        const Ray ray = p.texel_ray(0, t + 0.5f);
        const float entry = reference_entry(v, ray, c.colors, kCssmEntryOpacity);
        const float stored = first_view.texels[tap.at + 3];
        if (entry < kInfinity) {
          ASSERT_NEAR(stored, entry, 1e-3f * v.step) << "entry of texel " << t.x << ", " << t.y;
        } else {
          ASSERT_EQ(stored, kInfinity);
        }
        ++entries_checked;
        sum += reference_transmittance(v, ray, tap.depth, c.colors);
      }
      ASSERT_GT(kept, 0);
      const vec3 e = sum / float(kept);
      if (max_component(glm::min(e, 1.0f - e)) < 0.05f) continue;  // no channel partly lit
      points.push_back(q);
      expected.push_back(e);
    }
    ASSERT_EQ(points.size(), 80u);
    const int seeds = 600;
    std::vector<dvec3> sum(points.size(), dvec3(0.0)), sum_sq(points.size(), dvec3(0.0));
    for (int seed = 0; seed < seeds; ++seed) {
      const LightMap map = build_cssm(v, p, std::uint32_t(seed), 0, c.colors);
      const LightMapView view = map.view();
      const CssmVisibility visibility = make_cssm_visibility(&view, 13, 1.0f, c.depth_aware);
      for (std::size_t i = 0; i < points.size(); ++i) {
        const dvec3 f(visibility(0, points[i], sample_light(light, points[i])));
        sum[i] += f;
        sum_sq[i] += f * f;
      }
    }
    int partial = 0;
    double worst_z = 0.0, z_sum = 0.0, z_sq_sum = 0.0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const dvec3 mean = sum[i] / double(seeds);
      const dvec3 variance = glm::max(sum_sq[i] / double(seeds) - mean * mean, dvec3(0.0));
      for (int ch = 0; ch < 3; ++ch) {
        const double standard_error = std::sqrt(variance[ch] / double(seeds));
        EXPECT_NEAR(mean[ch], expected[i][ch], 4.5 * standard_error + 1e-3) << "point " << i << " channel " << ch;
        if (!(expected[i][ch] > 0.05f && expected[i][ch] < 0.95f) || standard_error <= 0.0) continue;
        const double z = (mean[ch] - expected[i][ch]) / standard_error;
        worst_z = std::max(worst_z, std::abs(z));
        z_sum += z;
        z_sq_sum += z * z;
        ++partial;
      }
    }
    const double mean_z = z_sum / partial, mean_z_sq = z_sq_sum / partial;
    std::printf("[cssm] unbiased, %s: %d partly lit channels, %d entries checked; z-score worst %.2f, mean %.3f, "
                "mean square %.3f\n",
                c.name, partial, entries_checked, worst_z, mean_z, mean_z_sq);
    EXPECT_GE(partial, 150) << "the test should probe partly shadowed samples";
    // Channels and neighbouring points share photons, so the z-scores are
    // correlated: the bounds are a few times the spread measured over seeds.
    EXPECT_LT(mean_z_sq, 1.6);
    EXPECT_LT(std::abs(mean_z), 0.6);
  }
}

TEST(Cssm, GenerationIsDeterministicPerSeed) {
  const Scene scene = cssm_spheres();
  SceneResources resources;
  resources.update(scene);
  const RenderView v = resources.view(scene);
  Light light;
  const LightProjection p = make_light_projection(light, v.box, 64);
  const ShadowColorModel colors;
  const LightMap a = build_cssm(v, p, 5, 0, colors);
  const LightMap b = build_cssm(v, p, 5, 0, colors);
  const LightMap c = build_cssm(v, p, 6, 0, colors);
  const LightMap other_light = build_cssm(v, p, 5, 1, colors);
  int differ_seed = 0, differ_light = 0, stopped = 0;
  for (std::int64_t i = 0; i < p.texel_count(); ++i) {
    for (int ch = 0; ch < 3; ++ch) {
      ASSERT_EQ(a.texel(i)[ch], b.texel(i)[ch]);
      differ_seed += a.texel(i)[ch] != c.texel(i)[ch];
      differ_light += a.texel(i)[ch] != other_light.texel(i)[ch];
      stopped += a.texel(i)[ch] < kInfinity;
    }
    ASSERT_EQ(a.texel(i)[3], c.texel(i)[3]) << "the entry depth is not random";
  }
  EXPECT_GT(stopped, 300);
  EXPECT_GT(differ_seed, stopped / 2);
  EXPECT_GT(differ_light, stopped / 2);
}

// A black opaque wall stops every channel in its first segment, at one
// depth shared by the channels. Under the paper's colours a blue wall lets
// every blue photon through; under the chromatic model it lets blue through
// more often than red, but stops some.
TEST(Cssm, ChannelsStopWhereTheirColourIsAbsorbed) {
  Scene scene = testing::procedural_scene("slab", ivec3(16));
  scene.set_transfer_function(testing::step_tf(0.0f, vec3(0.0f), 1.0f));
  SceneResources resources;
  resources.update(scene);
  Light light;
  const LightProjection p = make_light_projection(light, resources.view(scene).box, 64);
  const LightMap black = build_cssm(resources.view(scene), p, 1, 0, ShadowColorModel{});
  const float entry = intersect_box(p.texel_ray(0, vec2(32.5f)), resources.view(scene).box, 0.0f, kInfinity).t0;
  const float* texel = black.view().texel(0, 32, 32);
  EXPECT_EQ(texel[0], texel[1]);
  EXPECT_EQ(texel[1], texel[2]);
  EXPECT_GE(texel[0], entry);
  EXPECT_LE(texel[0], entry + resources.view(scene).step);

  scene.set_transfer_function(testing::step_tf(0.0f, vec3(0.0f, 0.0f, 1.0f), 0.1f));
  resources.update(scene);
  for (ShadowColor kind : {ShadowColor::Paper, ShadowColor::Chromatic}) {
    const LightMap blue = build_cssm(resources.view(scene), p, 1, 0, ShadowColorModel{kind});
    int blue_through = 0, red_through = 0;
    for (std::int64_t i = 0; i < p.texel_count(); ++i) {
      blue_through += blue.texel(i)[2] == kInfinity;
      red_through += blue.texel(i)[0] == kInfinity;
    }
    if (kind == ShadowColor::Paper) {
      EXPECT_EQ(blue_through, p.texel_count());
    } else {
      EXPECT_LT(blue_through, p.texel_count() * 9 / 10) << "chromatic: the blue wall still shadows blue";
      EXPECT_GT(blue_through, red_through + p.texel_count() / 10) << "chromatic: blue passes more often";
    }
  }
}

TEST(Cssm, OffsetsFollowThePaperInTexelsOfTheMap) {
  LightMapView map;
  for (int resolution : {256, 1024, 4096}) {
    map.projection.resolution = resolution;
    for (int count : {7, 13, 21, 37}) {
      const CssmVisibility v = make_cssm_visibility(&map, count, 1.0f);
      EXPECT_EQ(v.offset_count, count);
      EXPECT_EQ(v.offset(map, 0), vec2(0.0f));
      vec2 sum(0.0f);
      for (int j = 0; j < count; ++j) sum += v.offset(map, j);
      if (count != 7) {
        EXPECT_EQ(sum, vec2(0.0f)) << "the 13, 21 and 37 sets are symmetric";
      }
    }
    const CssmVisibility paper = make_cssm_visibility(&map, kMaxCssmOffsets, 1.0f);
    const vec2 expected[13] = {{0, 0}, {3, 3}, {-3, 3}, {3, -3}, {-3, -3}, {4, 0}, {-4, 0},
                               {0, 4}, {0, -4}, {7, 0}, {-7, 0}, {0, 7}, {0, -7}};
    for (int j = 0; j < 13; ++j) EXPECT_EQ(paper.offset(map, j), expected[j]) << resolution;
    EXPECT_EQ(make_cssm_visibility(&map, 13, 0.5f).offset(map, 9), vec2(3.5f, 0.0f));
    // No two offsets of the largest set fall on one texel.
    for (int a = 0; a < kMaxCssmOffsets; ++a) {
      for (int b = a + 1; b < kMaxCssmOffsets; ++b) EXPECT_NE(paper.offsets[a], paper.offsets[b]) << a << " " << b;
    }
  }
}

}  // namespace
}  // namespace penumbra

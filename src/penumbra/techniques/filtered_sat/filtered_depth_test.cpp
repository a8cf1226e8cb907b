// The filtered optical depth of the CSAT and SSAT lookups against brute
// force: shadow rays over an I x J grid of the patch (Ament et al. 2014,
// eqs. 5 and 12), marched through the same trilinear volume and TF.
#include "penumbra/base/rng.h"
#include "penumbra/render/march.h"
#include "penumbra/render/scene_resources.h"
#include "penumbra/techniques/filtered_sat/light_tables.h"
#include "penumbra/techniques/filtered_sat/orthodirectional_groups.h"
#include "penumbra/techniques/filtered_sat/shadow_filter.h"
#include "test_scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace penumbra {
namespace {

// Spheres with an extinction that varies smoothly inside them (alpha 0 at
// value 0.05 rising to 0.3 at 1), so the tables' point samples and the brute
// force see the same field up to discretisation.
Scene smooth_spheres() {
  Scene scene = testing::procedural_scene("spheres", ivec3(48), 8);
  TransferFunction tf({{0.0f, vec3(1.0f), 0.0f}, {0.05f, vec3(1.0f), 0.0f}, {1.0f, vec3(1.0f), 0.3f}});
  tf.set_range(vec2(0.0f, 1.0f));
  scene.set_transfer_function(tf);
  return scene;
}

// Optical depth of a ray from `from` along unit `dir` over [0, length],
// midpoint rule with a 0.1-voxel step (converged to < 1e-3 here).
float brute_depth(const RenderView& v, vec3 from, vec3 dir, float length) {
  const Interval chord = volume_interval(v, Ray{from, dir}, 0.0f, length);
  if (chord.empty()) return 0.0f;
  const float dt = 0.1f;
  const int n = int(std::ceil(chord.length() / dt));
  const float h = chord.length() / float(n);
  double depth = 0.0;
  for (int k = 0; k < n; ++k) {
    const vec3 p = from + (chord.t0 + (float(k) + 0.5f) * h) * dir;
    depth += v.tf.lookup(v.volume.sample(p)).a * h;
  }
  return float(depth);
}

constexpr int kPatchRays = 10;  // I = J: the patch's brute-force grid

// Eq. 12: mean over the patch [-S, S]^2 (axes ra, rb) of the optical depth of
// the rays toward the light, from the sample's plane.
float brute_cuboid(const RenderView& v, vec3 p, vec3 to_light, vec3 ra, vec3 rb, float half) {
  double sum = 0.0;
  for (int j = 0; j < kPatchRays; ++j)
    for (int i = 0; i < kPatchRays; ++i) {
      const float a = -half + (float(i) + 0.5f) * 2.0f * half / kPatchRays;
      const float b = -half + (float(j) + 0.5f) * 2.0f * half / kPatchRays;
      sum += brute_depth(v, p + a * ra + b * rb, to_light, kInfinity);
    }
  return float(sum / (kPatchRays * kPatchRays));
}

// Eqs. 16-21 and 5: the tangent square at the sample projected onto the
// sphere of radius R about the light, and the rays from there to the light.
float brute_pyramid(const RenderView& v, const SphericalTableGrid& g, vec3 p, float half) {
  const vec3 s = g.spherical_from_world(p);
  const vec3 r_phi = -std::sin(s.x) * g.axes[0] + std::cos(s.x) * g.axes[1];
  const vec3 r_theta = std::cos(s.y) * std::cos(s.x) * g.axes[0] + std::cos(s.y) * std::sin(s.x) * g.axes[1] -
                       std::sin(s.y) * g.axes[2];
  double sum = 0.0;
  for (int j = 0; j < kPatchRays; ++j)
    for (int i = 0; i < kPatchRays; ++i) {
      const float a = -half + (float(i) + 0.5f) * 2.0f * half / kPatchRays;
      const float b = -half + (float(j) + 0.5f) * 2.0f * half / kPatchRays;
      const vec3 on_sphere = g.light + s.z * glm::normalize(p + a * r_phi + b * r_theta - g.light);
      sum += brute_depth(v, on_sphere, glm::normalize(g.light - on_sphere), s.z);
    }
  return float(sum / (kPatchRays * kPatchRays));
}

struct Errors {
  double mean = 0.0;  // of |T_lookup - T_reference|, T = exp(-tau)
  double max = 0.0;
};

// Random samples in the volume box where the reference optical depth (from
// `brute`, on the geometry of the resolution-1 tables, which does not depend
// on the resolution) is at least 0.05, and the transmittance errors of the
// lookups at 1 and 2 table cells per voxel there.
template <class Brute>
std::pair<Errors, Errors> compare_lookups(const Scene& scene, const Light& light, float filter_voxels, Brute brute,
                                          int count) {
  SceneResources resources;
  resources.update(scene);
  const RenderView v = resources.shadow_view(scene);
  LightTables coarse, fine;
  coarse.build(v, {light}, 1.0f);
  fine.build(v, {light}, 0.5f);
  const ShadowFilter filter = make_shadow_filter(FilterKernel::Box, filter_voxels, 1.0f);
  Pcg32 rng(17);
  Errors e1, e2;
  int n = 0;
  while (n < count) {
    const vec3 p = v.box.lower + vec3(rng.next_float(), rng.next_float(), rng.next_float()) * v.box.extent();
    const float reference = brute(v, coarse.lookups()[0], p, filter.half_width);
    if (reference < 0.05f) continue;  // lit: nothing to compare
    const double t = std::exp(-double(reference));
    const double d1 = std::abs(std::exp(-double(filtered_optical_depth(coarse.lookups()[0], filter, p))) - t);
    const double d2 = std::abs(std::exp(-double(filtered_optical_depth(fine.lookups()[0], filter, p))) - t);
    e1.mean += d1 / count;
    e2.mean += d2 / count;
    e1.max = std::max(e1.max, d1);
    e2.max = std::max(e2.max, d2);
    ++n;
  }
  return {e1, e2};
}

// Transmittance errors of the box-filtered CSAT lookup against eq. 12. The
// table holds sigma_t at cell centres as a cell-wise constant density: inside
// the cuboid that is the midpoint rule (second order), but cells cut by the
// cuboid's faces and by the sample's plane count in proportion to the cut
// volume, a first-order error in the cell size that shows where the field
// is steep. Observed: mean 0.0012-0.0027, worst 0.010 at one cell per
// voxel; at two, half to a quarter of that, down to the brute force's own
// error (10 x 10 rays over the patch, 0.1-voxel steps), about 0.0007.
// Asserted: mean 0.005, worst 0.02 at one cell per voxel, and the mean 30%
// smaller at two cells per voxel.
TEST(FilteredDepth, CsatBoxFilterMatchesShadowRaysOverThePatch) {
  const Scene scene = smooth_spheres();
  Pcg32 rng(3);
  for (int trial = 0; trial < 3; ++trial) {
    Light light;
    light.direction = glm::normalize(vec3(rng.next_float() - 0.5f, rng.next_float() - 0.5f, -0.6f));
    const float filter = trial == 0 ? 3.0f : 8.0f;
    auto brute = [&](const RenderView& v, const LightTableLookup& l, vec3 p, float half) {
      const vec3 ra = l.cartesian.axes[l.axis == 0 ? 1 : 0];
      const vec3 rb = l.cartesian.axes[l.axis == 2 ? 1 : 2];
      return brute_cuboid(v, p, -light.direction, ra, rb, half);
    };
    SCOPED_TRACE(::testing::Message() << "trial " << trial << " filter " << filter);
    const auto [coarse, fine] = compare_lookups(scene, light, filter, brute, 30);
    std::printf("CSAT filter %.0f: |dT| mean %.4f max %.4f (1 cell/voxel), mean %.4f max %.4f (2 cells/voxel)\n",
                filter, coarse.mean, coarse.max, fine.mean, fine.max);
    EXPECT_LT(coarse.mean, 0.005);
    EXPECT_LT(coarse.max, 0.02);
    EXPECT_LT(fine.mean, 0.7 * coarse.mean);
  }
}

// The same for the SSAT against eqs. 16-21: besides the table's
// discretisation, the lookup's patch is the (phi, theta) box spanned by the
// projected square's axes, weighted by solid angle, while eq. 5 weights the
// projected square uniformly in (u, v); the two differ by O((S / R)^2),
// small for the samples compared (R >= 8 S). Observed: mean 0.0014-0.0027,
// worst 0.009 at one cell per voxel, a third of that at two; asserted as
// for the CSAT.
TEST(FilteredDepth, SsatBoxFilterMatchesShadowRaysOverThePatch) {
  const Scene scene = smooth_spheres();
  const vec3 positions[] = {vec3(3.0f, -2.0f, 4.0f), vec3(70.0f, -50.0f, 40.0f), vec3(-10.0f, 30.0f, -35.0f)};
  for (const vec3& position : positions) {
    Light light;
    light.type = LightType::Point;
    light.position = position;
    const float filter = 4.0f;
    auto brute = [&](const RenderView& v, const LightTableLookup& l, vec3 p, float half) {
      if (glm::length(p - position) < 8.0f * 2.0f * half) return 0.0f;  // too close to the light for the patch
      return brute_pyramid(v, l.spherical, p, half);
    };
    SCOPED_TRACE(::testing::Message() << "light at " << position.x << ", " << position.y << ", " << position.z);
    const auto [coarse, fine] = compare_lookups(scene, light, filter, brute, 30);
    std::printf("SSAT: |dT| mean %.4f max %.4f (1 cell/voxel), mean %.4f max %.4f (2 cells/voxel)\n", coarse.mean,
                coarse.max, fine.mean, fine.max);
    EXPECT_LT(coarse.mean, 0.005);
    EXPECT_LT(coarse.max, 0.02);
    EXPECT_LT(fine.mean, 0.7 * coarse.mean);
  }
}

// Eq. 25 by brute force: the patch split into the filter's taps x taps
// sub-patches, each one's mean optical depth from 2 x 2 rays through it,
// weighted by the product of the taps' weights.
template <class RayDepth>
float brute_gaussian(const ShadowFilter& filter, RayDepth ray_depth) {
  constexpr int kRaysPerTap = 2;
  const float step = 2.0f * filter.half_width / float(filter.taps);
  double depth = 0.0;
  for (int j = 0; j < filter.taps; ++j)
    for (int i = 0; i < filter.taps; ++i) {
      double sum = 0.0;
      for (int y = 0; y < kRaysPerTap; ++y)
        for (int x = 0; x < kRaysPerTap; ++x) {
          const float a = -filter.half_width + step * (float(i) + (float(x) + 0.5f) / kRaysPerTap);
          const float b = -filter.half_width + step * (float(j) + (float(y) + 0.5f) / kRaysPerTap);
          sum += ray_depth(a, b);
        }
      depth += double(filter.weights[i]) * filter.weights[j] * sum / (kRaysPerTap * kRaysPerTap);
    }
  return float(depth);
}

// The Gaussian lookups (8 x 8 sub-cuboids of the CSAT, 8 x 8 sub-pyramids of
// the SSAT) against eq. 25 by brute force, for an oblique directional light
// and point lights inside and outside the volume, at one table cell per
// voxel. A sub-patch is an eighth of the patch (0.9 voxels for this 4-voxel
// filter), about a cell, so each sub-cuboid carries the first-order error of
// the cells its faces cut, but the errors of neighbouring sub-cuboids cancel
// in the weighted sum (they share their faces). Samples the table finds lit
// are skipped before the (costly) brute force. Observed: mean |dT|
// 0.0009-0.0026, worst 0.006; asserted as for the box: mean 0.005, worst 0.02.
TEST(FilteredDepth, GaussianLookupsMatchWeightedShadowRays) {
  const Scene scene = smooth_spheres();
  SceneResources resources;
  resources.update(scene);
  const RenderView v = resources.shadow_view(scene);
  const ShadowFilter filter = make_shadow_filter(FilterKernel::Gaussian, 4.0f, 1.0f);
  ASSERT_EQ(filter.taps, ShadowFilter::kMaxTaps);
  Light directional;
  directional.direction = glm::normalize(vec3(0.3f, -0.5f, -0.8f));
  Light inside, outside;
  inside.type = outside.type = LightType::Point;
  inside.position = vec3(3.0f, -2.0f, 4.0f);
  outside.position = vec3(70.0f, -50.0f, 40.0f);
  for (const Light& light : {directional, inside, outside}) {
    SCOPED_TRACE(::testing::Message() << "light type " << int(light.type));
    LightTables tables;
    tables.build(v, {light}, 1.0f);
    const LightTableLookup& lookup = tables.lookups()[0];
    Pcg32 rng(29);
    double mean = 0.0, worst = 0.0;
    int n = 0;
    constexpr int kSamples = 12;
    for (int attempt = 0; n < kSamples && attempt < 100000; ++attempt) {
      const vec3 p = v.box.lower + vec3(rng.next_float(), rng.next_float(), rng.next_float()) * v.box.extent();
      const float lookup_depth = filtered_optical_depth(lookup, filter, p);
      if (lookup_depth < 0.03f) continue;
      float reference = 0.0f;
      if (lookup.kind == LightTableKind::Cartesian) {
        const vec3 ra = lookup.cartesian.axes[lookup.axis == 0 ? 1 : 0];
        const vec3 rb = lookup.cartesian.axes[lookup.axis == 2 ? 1 : 2];
        reference = brute_gaussian(filter, [&](float a, float b) {
          return brute_depth(v, p + a * ra + b * rb, -light.direction, kInfinity);
        });
      } else {
        const SphericalTableGrid& g = lookup.spherical;
        const vec3 s = g.spherical_from_world(p);
        // Too close to the light for the patch (+-3 sigma here): the lookup's
        // (phi, theta) boxes and eq. 5's square differ by O((S / R)^2).
        if (s.z < 8.0f * filter.half_width) continue;
        const vec3 r_phi = -std::sin(s.x) * g.axes[0] + std::cos(s.x) * g.axes[1];
        const vec3 r_theta = std::cos(s.y) * std::cos(s.x) * g.axes[0] + std::cos(s.y) * std::sin(s.x) * g.axes[1] -
                             std::sin(s.y) * g.axes[2];
        reference = brute_gaussian(filter, [&](float a, float b) {
          const vec3 on_sphere = g.light + s.z * glm::normalize(p + a * r_phi + b * r_theta - g.light);
          return brute_depth(v, on_sphere, glm::normalize(g.light - on_sphere), s.z);
        });
      }
      if (reference < 0.05f) continue;  // lit: nothing to compare
      const double d = std::abs(std::exp(-double(lookup_depth)) - std::exp(-double(reference)));
      mean += d / kSamples;
      worst = std::max(worst, d);
      ++n;
    }
    ASSERT_EQ(n, kSamples);
    std::printf("Gaussian, light type %d: |dT| mean %.4f max %.4f\n", int(light.type), mean, worst);
    EXPECT_LT(mean, 0.005);
    EXPECT_LT(worst, 0.02);
  }
}

TEST(OrthodirectionalGroups, SixAxesShareOneFrameAndOthersGetTheirOwn) {
  const vec3 a = glm::normalize(vec3(1.0f, 1.0f, 0.0f));
  const vec3 b = glm::normalize(vec3(-1.0f, 1.0f, 0.3f));
  const vec3 c = glm::normalize(glm::cross(a, b));
  const vec3 b_exact = glm::cross(c, a);
  const OrthodirectionalGrouping g =
      group_orthodirectional({a, -a, b_exact, c, -b_exact, -c, a, glm::normalize(a + 0.1f * c)});
  ASSERT_EQ(g.groups.size(), 2u);
  for (int i = 0; i < 7; ++i) EXPECT_EQ(g.members[std::size_t(i)].group, 0) << i;
  EXPECT_EQ(g.members[7].group, 1);
  // Each member's axis and sign point at its light.
  const vec3 dirs[] = {a, -a, b_exact, c, -b_exact, -c, a};
  for (int i = 0; i < 7; ++i) {
    const OrthodirectionalMember& m = g.members[std::size_t(i)];
    EXPECT_GT(glm::dot(m.sign * g.groups[0].axes[m.axis], dirs[i]), 0.9999f) << i;
  }
  const vec3* f = g.groups[0].axes;
  EXPECT_NEAR(glm::dot(glm::cross(f[0], f[1]), f[2]), 1.0f, 1e-5f);
  // A lone light is the w axis of a frame that follows the world axes.
  const OrthodirectionalGrouping single = group_orthodirectional({vec3(0.0f, 0.0f, 1.0f)});
  EXPECT_EQ(single.members[0].axis, 2);
  EXPECT_NEAR(single.groups[0].axes[0].x, 1.0f, 1e-6f);
}

}  // namespace
}  // namespace penumbra

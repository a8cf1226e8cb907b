// Analytic checks of the shared marching loop: exact homogeneous
// transmittance, empty-space skipping that costs no samples and changes
// nothing, step independence through opacity correction, early ray
// termination and clip planes.
#include "penumbra/render/lighting.h"
#include "penumbra/render/majorant_grid.h"
#include "penumbra/render/march.h"
#include "penumbra/render/render_loop.h"
#include "penumbra/render/sample_cursor.h"
#include "penumbra/render/scene_resources.h"
#include "test_scene.h"

#include <gtest/gtest.h>

#include <cmath>

namespace penumbra {
namespace {

using testing::procedural_scene;
using testing::step_tf;

TEST(SampleGrid, SegmentsPartitionTheIntervalAndSamplesAreOrdered) {
  for (float step : {0.3f, 0.5f, 1.0f, 7.0f}) {
    for (float offset : {0.0f, 0.5f, 0.9f}) {
      const SampleGrid grid(Interval{1.25f, 11.0f}, step, offset);
      float total = 0.0f;
      for (int k = 0; k < grid.count; ++k) {
        total += grid.length(k);
        EXPECT_GT(grid.length(k), 0.0f);
        EXPECT_GE(grid.position(k), grid.start(k));
        if (k > 0) {
          EXPECT_GT(grid.position(k), grid.position(k - 1));
        }
      }
      EXPECT_NEAR(total, 9.75f, 1e-4f);
      for (float t : {1.0f, 1.25f, 3.3f, 10.99f, 12.0f}) {
        const int k = grid.first_at_or_after(t);
        if (k < grid.count) {
          EXPECT_GE(grid.position(k), t);
        }
        if (k > 0) {
          EXPECT_LT(grid.position(k - 1), t);
        }
      }
    }
  }
}

// Transmittance through the homogeneous `slab` volume equals exp(-sigma d)
// for rays in many directions; the segment lengths add up to the chord, so
// the error is float rounding only (the issue asks for 1% at step <= 0.5).
TEST(March, SlabTransmittanceIsExact) {
  Scene scene = procedural_scene("slab", ivec3(40, 30, 20));
  scene.set_transfer_function(step_tf(0.0f, vec3(1.0f), 0.05f));
  SceneResources resources;
  resources.update(scene);
  const RenderView v = resources.view(scene);
  const float sigma = -std::log(1.0f - 0.05f);  // unit_length = 1 voxel
  Pcg32 rng(3);
  for (float step_voxels : {0.5f, 0.25f, 0.9f}) {
    RenderView vs = v;
    vs.step = step_voxels;
    for (int trial = 0; trial < 200; ++trial) {
      const vec3 dir = glm::normalize(vec3(rng.next_float() - 0.5f, rng.next_float() - 0.5f, rng.next_float() - 0.5f));
      const vec3 inside = v.box.lower + vec3(rng.next_float(), rng.next_float(), rng.next_float()) * v.box.extent();
      const Ray ray{inside, dir};
      const Interval chord = intersect_box(ray, v.box, 0.0f, kInfinity);
      RayStats stats;
      const float t = march_transmittance(vs, ray, kInfinity, 1.0f, stats);
      const float expected = std::exp(-sigma * chord.length());
      ASSERT_NEAR(t, expected, 0.01f * expected + 1e-6f) << "step " << step_voxels;
    }
  }
}

TEST(March, RaysThroughEmptySpaceTakeNoSamples) {
  Scene scene = procedural_scene("spheres", ivec3(64));
  scene.set_transfer_function(step_tf(0.05f, vec3(1.0f), 0.5f));
  SceneResources resources;
  resources.update(scene);
  const RenderView v = resources.view(scene);
  // Along the box's bottom-front edge region no sphere reaches (all spheres
  // lie within |p| < 0.85 of the centre in normalised units).
  const Ray empty{vec3(-40.0f, v.box.lower.y + 1.0f, v.box.lower.z + 1.0f), vec3(1.0f, 0.0f, 0.0f)};
  RayStats stats;
  EXPECT_FLOAT_EQ(march_transmittance(v, empty, kInfinity, 1.0f, stats), 1.0f);
  EXPECT_EQ(stats.samples, 0u);
  const vec4 c = march_ray(v, VolumeSampler<float>(v.volume.data, v.volume.dims), empty, 0.5f, EmissionLighting{&v}, stats);
  EXPECT_EQ(stats.samples, 0u);
  EXPECT_FLOAT_EQ(c.a, 0.0f);
  // Through a sphere centre: samples are taken, but fewer than without skipping.
  const vec3 center = v.volume.world_from_index((kSpheres[0].center + 1.0f) * 31.5f);
  const Ray through{vec3(v.box.lower.x - 5.0f, center.y, center.z), vec3(1.0f, 0.0f, 0.0f)};
  RayStats hit;
  march_transmittance(v, through, kInfinity, 1.0f, hit);
  EXPECT_GT(hit.samples, 0u);
  EXPECT_LT(float(hit.samples), v.box.extent().x / v.step);
}

// The cursor, brute force: along rays in every direction, it gives exactly
// the samples of the grid whose position lies in an occupied macrocell, in
// order, for an occupancy of large blocks (long runs and empty cubes to
// jump), a ball and scattered single cells. Only a sample within rounding of a cell
// face may go either way.
TEST(March, CursorTakesExactlyTheSamplesInOccupiedCells) {
  Scene scene = procedural_scene("spheres", ivec3(128), 32);
  SceneResources resources;
  resources.update(scene);
  RenderView v = resources.view(scene);
  const ivec3 cells = v.macrocells.dims;
  const int size = v.macrocells.cell_size;
  ASSERT_EQ(cells, ivec3(16));
  std::vector<float> majorant(std::size_t(cells.x) * cells.y * cells.z, 0.0f);
  auto at = [&](ivec3 c) { return std::size_t(c.x + cells.x * (c.y + cells.y * c.z)); };
  Pcg32 pick(11);
  for (int z = 0; z < cells.z; ++z)
    for (int y = 0; y < cells.y; ++y)
      for (int x = 0; x < cells.x; ++x) {
        const bool block = x >= 2 && x <= 9 && y >= 1 && y <= 12 && z >= 3 && z <= 8;
        const bool ball = glm::length(vec3(x, y, z) - vec3(11.5f)) < 4.0f;
        const bool single = pick.next_float() < 0.05f;
        majorant[at(ivec3(x, y, z))] = (block || ball || single) ? 1.0f : 0.0f;
      }
  const std::vector<std::uint8_t> distances = empty_space_distance(majorant, cells);
  v.majorants = majorant.data();
  v.empty_distance = distances.data();
  auto occupied_at = [&](vec3 p, float& face) {
    const vec3 q = p / float(size);
    const vec3 f = q - glm::floor(q);
    face = glm::min(glm::min(glm::min(f.x, 1.0f - f.x), glm::min(f.y, 1.0f - f.y)), glm::min(f.z, 1.0f - f.z));
    const ivec3 c = glm::clamp(ivec3(glm::floor(q)), ivec3(0), cells - 1);
    return majorant[at(c)] > 0.0f;
  };
  Pcg32 rng(5);
  int rays = 0, taken = 0, skipped = 0, ambiguous = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const vec3 target = v.box.lower + vec3(rng.next_float(), rng.next_float(), rng.next_float()) * v.box.extent();
    const vec3 dir = glm::normalize(vec3(rng.next_float() - 0.5f, rng.next_float() - 0.5f, rng.next_float() - 0.5f));
    const Ray ray{target - 300.0f * dir, dir};
    const Interval iv = intersect_box(ray, v.box, 0.0f, kInfinity);
    if (iv.empty()) continue;
    ++rays;
    const float step = trial % 3 == 0 ? 0.37f : (trial % 3 == 1 ? 1.0f : 2.3f);
    const SampleGrid grid(iv, step, rng.next_float());
    std::vector<int> got;
    SampleCursor cursor(v, ray, grid);
    int k;
    float t;
    while (cursor.next(k, t)) {
      ASSERT_FLOAT_EQ(t, grid.position(k));
      if (!got.empty()) {
        ASSERT_GT(k, got.back());
      }
      got.push_back(k);
    }
    std::size_t next = 0;
    for (int j = 0; j < grid.count; ++j) {
      float face = 0.0f;
      const bool want = occupied_at(v.volume.index_from_world(ray.origin + grid.position(j) * ray.direction), face);
      const bool has = next < got.size() && got[next] == j;
      if (has) ++next;
      if (face < 2e-5f) {
        ++ambiguous;
        continue;
      }
      ASSERT_EQ(has, want) << "trial " << trial << " sample " << j << " of " << grid.count;
      (want ? taken : skipped) += 1;
    }
    ASSERT_EQ(next, got.size());
  }
  EXPECT_GT(rays, 300);
  EXPECT_GT(taken, 10000);
  EXPECT_GT(skipped, 10000);
  EXPECT_LT(ambiguous, (taken + skipped) / 1000) << taken << " taken, " << skipped << " skipped";
}

TEST(March, SkippingChangesNoPixel) {
  Scene scene = procedural_scene("spheres", ivec3(48), 32);
  scene.set_transfer_function(step_tf(0.3f, vec3(0.8f, 0.5f, 0.2f), 0.3f));
  SceneResources resources;
  resources.update(scene);
  const RenderView v = resources.view(scene);
  std::vector<float> all_occupied(resources.majorants().majorant.size(), 1.0f);
  std::vector<std::uint8_t> no_empty(all_occupied.size(), 0);
  RenderView no_skip = v;
  no_skip.majorants = all_occupied.data();
  no_skip.empty_distance = no_empty.data();
  Image skipped, full;
  RenderStats s1, s2;
  render_image(v, [&](const auto&) { return EmissionLighting{&v}; }, skipped, &s1);
  render_image(no_skip, [&](const auto&) { return EmissionLighting{&no_skip}; }, full, &s2);
  for (std::size_t i = 0; i < skipped.pixel_count(); ++i) {
    ASSERT_NEAR(skipped.data()[i].r, full.data()[i].r, 1e-6f);
    ASSERT_NEAR(skipped.data()[i].a, full.data()[i].a, 1e-6f);
  }
  EXPECT_LT(s1.samples, s2.samples / 2);  // most of the box is empty
}

// Opacity correction: the same TF rendered at steps 1/4, 1/2 and 1 voxel
// gives the same image up to the discretisation error of the step. The
// spheres' smooth linear profile keeps that error small: we allow a mean
// absolute difference of 0.5% and a max of 3% of full scale.
TEST(March, OpacityCorrectionMakesImagesIndependentOfStep) {
  Scene scene = procedural_scene("spheres", ivec3(48), 40);
  scene.set_transfer_function(TransferFunction({{0.0f, vec3(0.2f, 0.4f, 1.0f), 0.0f},
                                                {1.0f, vec3(1.0f, 0.8f, 0.4f), 0.6f}}));
  TransferFunction tf = scene.transfer_function();
  tf.set_range(vec2(0.0f, 1.0f));
  scene.set_transfer_function(tf);
  auto render_at = [&](float step) {
    RenderSettings r = scene.render();
    r.step = step;
    r.ert_threshold = 1.0f;
    scene.set_render(r);
    return testing::render_with(scene, "emission-absorption");
  };
  const Image fine = render_at(0.25f);
  for (float step : {0.5f, 1.0f}) {
    const Image coarse = render_at(step);
    double sum = 0.0, worst = 0.0;
    for (std::size_t i = 0; i < fine.pixel_count(); ++i) {
      for (int c = 0; c < 3; ++c) {
        const double d = std::abs(double(fine.data()[i][c]) - double(coarse.data()[i][c]));
        sum += d;
        worst = std::max(worst, d);
      }
    }
    EXPECT_LT(sum / (3.0 * double(fine.pixel_count())), 0.005) << "step " << step;
    EXPECT_LT(worst, 0.03) << "step " << step;
  }
}

TEST(March, EarlyRayTerminationStopsAtTheThreshold) {
  Scene scene = procedural_scene("slab", ivec3(32));
  scene.set_transfer_function(step_tf(0.0f, vec3(1.0f), 0.3f));
  SceneResources resources;
  resources.update(scene);
  RenderView v = resources.view(scene);
  const Ray ray{vec3(-100.0f, 0.0f, 0.0f), vec3(1.0f, 0.0f, 0.0f)};
  RayStats with_ert, without;
  v.ert_threshold = 0.99f;
  const VolumeSampler<float> sampler(v.volume.data, v.volume.dims);
  const vec4 a = march_ray(v, sampler, ray, 0.5f, EmissionLighting{&v}, with_ert);
  v.ert_threshold = 1.0f;
  const vec4 b = march_ray(v, sampler, ray, 0.5f, EmissionLighting{&v}, without);
  EXPECT_GE(a.a, 0.99f);
  EXPECT_LT(with_ert.samples, without.samples);
  // sigma = -ln(0.7) per voxel, step 0.5: opacity 0.99 after ln(100)/sigma voxels.
  EXPECT_NEAR(float(with_ert.samples), std::ceil(std::log(100.0f) / -std::log(0.7f) / 0.5f), 1.0f);
  EXPECT_NEAR(b.r, 1.0f - std::exp(std::log(0.7f) * 31.0f), 1e-4f);
}

TEST(March, ClipPlanesEmptyTheClippedSide) {
  Scene scene = procedural_scene("slab", ivec3(32), 24);
  scene.set_transfer_function(step_tf(0.0f, vec3(1.0f), 0.2f));
  scene.set_clip_planes({vec4(1.0f, 0.0f, 0.0f, 0.0f)});  // keep x >= 0
  SceneResources resources;
  resources.update(scene);
  const RenderView v = resources.view(scene);
  RayStats stats;
  // A ray along -x through the clipped half only sees x in [0, 15.5].
  const float t = march_transmittance(v, Ray{vec3(100.0f, 0.0f, 0.0f), vec3(-1.0f, 0.0f, 0.0f)}, kInfinity, 1.0f, stats);
  EXPECT_NEAR(t, std::exp(std::log(0.8f) * 15.5f), 1e-4f);
  // Viewing along +y (the framing camera), the left half of the image is empty.
  const Image image = testing::render_with(scene, "emission-absorption");
  EXPECT_LT(testing::mean_rgb(image, 0, 0, 11, 24).r, 1e-6f);
  EXPECT_GT(testing::mean_rgb(image, 13, 8, 16, 16).r, 0.5f);
}

}  // namespace
}  // namespace penumbra

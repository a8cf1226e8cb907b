// filtered-sat's streamed tables (issue 22, memory of a 512^3 volume): the
// depths of the layer-by-layer stream against the light's whole table, and
// the technique's images with and without streaming.
#include "penumbra/analysis/image_metrics.h"
#include "penumbra/base/rng.h"
#include "penumbra/render/scene_resources.h"
#include "penumbra/techniques/filtered_sat/filtered_sat_test_scenes.h"
#include "penumbra/techniques/filtered_sat/light_tables.h"
#include "penumbra/techniques/filtered_sat/shadow_filter.h"
#include "penumbra/techniques/filtered_sat/streamed_table.h"
#include "penumbra/techniques/registry.h"
#include "penumbra/techniques/sat_common/extinction_table.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace penumbra {
namespace {

using testing::sat_spheres;

struct Difference {
  double max = 0.0;        // of |depth_stream - depth_table|
  double max_depth = 0.0;  // the largest table depth seen
  bool full_turn = false;  // an SSAT around its light
};

// Random points over the box and a little beyond it, their depths from the
// light's table and from the stream.
Difference stream_against_table(const Scene& scene, float cell, const ShadowFilter& filter) {
  SceneResources resources;
  resources.update(scene);
  const RenderView v = resources.shadow_view(scene);
  LightTables tables;
  tables.build(v, scene.lights(), cell);
  const LightTableLookup& whole = tables.lookups()[0];
  const LightTableLookup light = LightTables::lookup_without_table(v.box, scene.lights(), cell, 0);
  EXPECT_EQ(light.kind, whole.kind);
  EXPECT_EQ(light.axis, whole.axis);
  EXPECT_EQ(light.sign, whole.sign);
  EXPECT_EQ(light.cartesian.cells, whole.cartesian.cells);
  EXPECT_EQ(light.spherical.cells, whole.spherical.cells);
  EXPECT_EQ(light.spherical.full_turn, whole.spherical.full_turn);
  const StreamedLightTable stream(v, light, extinction_samples_per_axis(cell / v.volume.min_spacing()));

  Pcg32 rng(5);
  std::vector<vec3> points(4000);
  const vec3 lower = v.box.lower - 0.1f * v.box.extent();
  for (vec3& p : points) p = lower + 1.2f * v.box.extent() * vec3(rng.next_float(), rng.next_float(), rng.next_float());
  std::vector<float> streamed(points.size(), -1.0f);
  stream.depths(filter, std::int64_t(points.size()), [&](std::int64_t i) { return points[std::size_t(i)]; },
                streamed.data());
  Difference d;
  d.full_turn = light.kind == LightTableKind::Spherical && light.spherical.full_turn;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double table = filtered_optical_depth(whole, filter, points[i]);
    d.max = std::max(d.max, std::abs(double(streamed[i]) - table));
    d.max_depth = std::max(d.max_depth, table);
  }
  return d;
}

// The stream's cells hold the values the table's cells hold (the centre,
// or the refined mean in surface cells) and its sums are exact in double,
// where the table keeps float prefix sums (with offsets): the depths agree
// to the table's rounding. Observed: at most 1.4e-6 of depths up to 7.2
// (relative 2e-7) over directional lights from either side of the three
// axes and point lights outside and inside the volume (whose SSATs wrap
// around), box and Gaussian filters, a patch offset, and cells of a half,
// one and two voxels. Asserted: 1e-6 relative to the deepest depth.
// Dropping the refinement in the stream (cells at their centre only) gives
// differences of 0.03-0.12 and fails it (not at half-voxel cells, which
// sample once), as does reading a CSAT's layers in the wrong order along
// the light (1.4-4.6) or an SSAT's cells with the measure of the next
// polar row.
TEST(StreamedLightTable, DepthsMatchTheLightsWholeTable) {
  const ShadowFilter box = make_shadow_filter(FilterKernel::Box, 3.0f, 1.0f);
  const ShadowFilter gaussian = make_shadow_filter(FilterKernel::Gaussian, 5.0f, 1.0f);
  const ShadowFilter offset = make_shadow_filter(FilterKernel::Box, 2.0f, 1.0f, 1.5f);
  struct Case {
    vec3 direction;  // a directional light's, or
    bool point;      // a point light at `direction`
    float cell;
    const ShadowFilter* filter;
  };
  const Case cases[] = {
      {vec3(0.4f, 0.6f, -1.0f), false, 1.0f, &box},      {vec3(-0.3f, 0.5f, 1.0f), false, 1.0f, &gaussian},
      {vec3(1.0f, 0.35f, -0.2f), false, 1.0f, &offset},  {vec3(-1.0f, 0.2f, 0.5f), false, 0.5f, &box},
      {vec3(0.2f, -1.0f, 0.3f), false, 2.0f, &gaussian}, {vec3(0.1f, 1.0f, 0.0f), false, 1.0f, &offset},
      {vec3(-30.0f, -40.0f, 45.0f), true, 1.0f, &box},   {vec3(35.0f, 10.0f, -30.0f), true, 1.0f, &gaussian},
      {vec3(2.0f, -3.0f, 1.0f), true, 1.0f, &offset},    {vec3(-1.0f, 2.0f, 0.5f), true, 0.5f, &box},
  };
  for (const Case& c : cases) {
    Scene scene = sat_spheres(c.point ? vec3(0.0f, 0.0f, -1.0f) : c.direction);
    if (c.point) {
      Light point;
      point.type = LightType::Point;
      point.position = c.direction;
      scene.set_lights({point});
    }
    const Difference d = stream_against_table(scene, c.cell, *c.filter);
    std::printf("%s (%.2f %.2f %.2f), cell %.1f: max difference %.3g of depths up to %.3g\n",
                c.point ? "point at" : "direction", c.direction.x, c.direction.y, c.direction.z, c.cell, d.max,
                d.max_depth);
    EXPECT_EQ(d.full_turn, c.point && glm::length(c.direction) < 10.0f);  // the lights inside wrap around
    EXPECT_GT(d.max_depth, 1.0);  // the points see the spheres
    EXPECT_LT(d.max, 1e-6 * d.max_depth);
  }
}

// The technique with its directional light streamed renders the image of
// its built table, with the same rebuilds and the same memory left after
// prepare (only the caches, bricks and floor grids), its directional and
// its point light streamed. Observed rmse 1.4e-7 (the depths' rounding
// through the bricks' 16-bit texels); without the stream's refinement
// 1.5e-4.
TEST(StreamedLightTable, StreamingLeavesTheImageAndTheCachesAsTheTableDoes) {
  Scene scene = testing::sat_spheres_and_a_point_light();
  scene.set_planes({Plane{vec3(0.0f, 0.0f, -30.0f), vec3(0.0f, 0.0f, 1.0f), vec3(0.5f)}});
  const TechniqueInfo& info = find_technique("filtered-sat");
  ParameterValues off(info.parameters), on(info.parameters);
  off.set("table_streaming", std::string("off"));
  on.set("table_streaming", std::string("on"));
  auto built = info.create();
  auto streamed = info.create();
  built->prepare(scene, off);
  streamed->prepare(scene, on);
  EXPECT_EQ(streamed->rebuilds(), built->rebuilds());
  EXPECT_EQ(streamed->aux_bytes(), built->aux_bytes());
  Image a, b;
  built->render(scene, a);
  streamed->render(scene, b);
  const double error = rmse(a, b);
  std::printf("streamed against built: rmse %.3g\n", error);
  EXPECT_LT(error, 1e-6);
  // Switching the streaming and a colour change rebuild nothing; a new
  // direction streams again.
  const std::uint64_t built_rebuilds = built->rebuilds();
  built->prepare(scene, on);
  EXPECT_EQ(built->rebuilds(), built_rebuilds);
  built->prepare(scene, off);
  const std::uint64_t before = streamed->rebuilds();
  Scene recoloured = scene;
  std::vector<Light> lights = scene.lights();
  lights[0].color = vec3(1.0f, 0.5f, 0.5f);
  recoloured.set_lights(lights);
  streamed->prepare(recoloured, on);
  EXPECT_EQ(streamed->rebuilds(), before);
  lights[0].direction = glm::normalize(vec3(-0.5f, 0.6f, -1.0f));
  Scene moved = scene;
  moved.set_lights(lights);
  streamed->prepare(moved, on);
  built->prepare(moved, off);
  EXPECT_GT(streamed->rebuilds(), before);
  streamed->render(moved, b);
  built->render(moved, a);
  EXPECT_LT(rmse(a, b), 1e-6);
}

}  // namespace
}  // namespace penumbra

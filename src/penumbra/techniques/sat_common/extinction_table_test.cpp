// Extinction tables on volume-aligned and rotated grids: the integral of a
// homogeneous medium, clip planes, grid fitting.
#include "penumbra/render/scene_resources.h"
#include "penumbra/techniques/sat_common/extinction_table.h"
#include "test_scene.h"

#include <gtest/gtest.h>

#include <cmath>

namespace penumbra {
namespace {

// A 32^3 slab (value 1 everywhere) with alpha 0.2 per voxel: sigma_t = -ln 0.8.
Scene slab_scene() {
  Scene scene = testing::procedural_scene("slab", ivec3(32), 8);
  scene.set_transfer_function(testing::step_tf(0.0f, vec3(1.0f), 0.2f));
  return scene;
}

const float kSigma = -std::log(0.8f);

TEST(CartesianTableGrid, FitsTheBoxInAnyFrame) {
  const Box3 box{vec3(-15.5f), vec3(15.5f)};
  vec3 u, v;
  complete_frame(vec3(0.0f, 0.0f, -2.0f), u, v);
  EXPECT_NEAR(glm::dot(u, vec3(1.0f, 0.0f, 0.0f)), 1.0f, 1e-6f) << "axis-aligned lights keep world axes";
  EXPECT_NEAR(glm::length(glm::cross(u, v) - vec3(0.0f, 0.0f, -1.0f)), 0.0f, 1e-6f) << "right-handed";
  const CartesianTableGrid aligned = fit_cartesian_grid(box, u, v, vec3(0.0f, 0.0f, -1.0f), 1.0f);
  EXPECT_EQ(aligned.cells, ivec3(31));
  const vec3 w = glm::normalize(vec3(1.0f, 2.0f, -2.0f));
  complete_frame(w, u, v);
  EXPECT_NEAR(glm::dot(u, v), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::dot(u, w), 0.0f, 1e-6f);
  const CartesianTableGrid rotated = fit_cartesian_grid(box, u, v, w, 0.5f);
  for (int corner = 0; corner < 8; ++corner) {
    const vec3 p((corner & 1) ? box.upper.x : box.lower.x, (corner & 2) ? box.upper.y : box.lower.y,
                 (corner & 4) ? box.upper.z : box.lower.z);
    const vec3 g = rotated.grid_from_world(p);
    for (int a = 0; a < 3; ++a) {
      EXPECT_GE(g[a], 0.0f);
      EXPECT_LE(g[a], float(rotated.cells[a]));
    }
    EXPECT_LT(glm::length(rotated.world_from_grid(g) - p), 1e-3f);
  }
}

TEST(ExtinctionTable, HomogeneousMediumIntegratesToSigmaTimesVolume) {
  const Scene scene = slab_scene();
  SceneResources resources;
  resources.update(scene);
  const RenderView view = resources.shadow_view(scene);
  const Box3 box = view.box;
  const double box_volume = double(box.extent().x) * box.extent().y * box.extent().z;

  // Volume-aligned, one cell per voxel: every cell centre is inside, exact.
  const CartesianTableGrid aligned = fit_cartesian_grid(box, vec3(1, 0, 0), vec3(0, 1, 0), vec3(0, 0, 1), 1.0f);
  const SummedAreaTable a = build_extinction_table(view, aligned, "aligned");
  EXPECT_NEAR(a.view().box_sum(vec3(0.0f), vec3(aligned.cells)), kSigma * box_volume, 1e-3 * kSigma * box_volume);
  // An interior box: sigma times its volume.
  EXPECT_NEAR(a.view().box_sum(vec3(3.25f, 4.0f, 5.5f), vec3(10.0f, 12.5f, 20.0f)),
              kSigma * 6.75 * 8.5 * 14.5, 1e-4);

  // Rotated: cells straddle the box faces and are point-sampled, so the
  // total is off by at most half a cell layer over the surface:
  // 6 * 31^2 * (0.5 * 0.5) / 31^3 = 2.4%; the errors of opposite faces
  // mostly cancel, 1.5% is asserted.
  vec3 u, v;
  const vec3 w = glm::normalize(vec3(0.3f, -0.5f, 0.8f));
  complete_frame(w, u, v);
  const CartesianTableGrid rotated = fit_cartesian_grid(box, u, v, w, 0.5f);
  const SummedAreaTable r = build_extinction_table(view, rotated, "rotated");
  EXPECT_NEAR(r.view().box_sum(vec3(0.0f), vec3(rotated.cells)), kSigma * box_volume, 0.015 * kSigma * box_volume);
  // Interior boxes of a homogeneous medium are exact in any frame.
  const vec3 centre = rotated.grid_from_world(vec3(0.0f));
  EXPECT_NEAR(r.view().box_sum(centre - 8.0f, centre + vec3(8.0f, 8.0f, 12.0f)), kSigma * 8.0 * 8.0 * 10.0, 1e-3);
}

TEST(ExtinctionTable, ClipPlanesRemoveWhatTheyCut) {
  Scene scene = slab_scene();
  scene.set_clip_planes({vec4(0.0f, 0.0f, 1.0f, 0.0f)});  // keeps z >= 0
  SceneResources resources;
  resources.update(scene);
  const RenderView view = resources.shadow_view(scene);
  const CartesianTableGrid grid = fit_cartesian_grid(view.box, vec3(1, 0, 0), vec3(0, 1, 0), vec3(0, 0, 1), 1.0f);
  const SummedAreaTable t = build_extinction_table(view, grid, "clipped");
  const SummedAreaTableView s = t.view();
  EXPECT_NEAR(s.box_sum(vec3(0.0f), vec3(31.0f, 31.0f, 15.0f)), 0.0, 1e-5);  // float residuals
  EXPECT_NEAR(s.box_sum(vec3(0.0f), vec3(31.0f)), kSigma * 31.0 * 31.0 * 16.0, 1e-3);
}

}  // namespace
}  // namespace penumbra

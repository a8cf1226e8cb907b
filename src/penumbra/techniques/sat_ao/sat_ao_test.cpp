// sat-ao: the occlusion of a homogeneous medium is analytic; the technique is
// light-independent and its cache interpolates the per-sample occlusion.
#include "penumbra/analysis/image_metrics.h"
#include "penumbra/techniques/registry.h"
#include "penumbra/techniques/sat_ao/ambient_occlusion.h"
#include "penumbra/techniques/sat_common/volume_aligned_table.h"
#include "test_scene.h"

#include <gtest/gtest.h>

#include <cmath>

namespace penumbra {
namespace {

using testing::procedural_scene;
using testing::render_with;

// In a homogeneous slab the mean extinction of a cube inside it is sigma, so
// the occlusion is exp(-sigma R); at a box corner only an eighth of the cube
// is inside: exp(-sigma R / 8).
TEST(SatAo, HomogeneousMediumGivesTheAnalyticOcclusion) {
  Scene scene = procedural_scene("slab", ivec3(32), 8);
  scene.set_transfer_function(testing::step_tf(0.0f, vec3(1.0f), 0.2f));
  SceneResources resources;
  resources.update(scene);
  VolumeAlignedTable table("test");
  ASSERT_TRUE(table.update(scene, resources, 1.0));
  EXPECT_FALSE(table.update(scene, resources, 1.0)) << "nothing changed";
  const float sigma = -std::log(0.8f);
  const AmbientOcclusion ao{table.view(), table.grid(), 5.0f, 1.0f};
  EXPECT_NEAR(ao.occlusion(vec3(1.3f, -2.0f, 0.7f)), std::exp(-sigma * 5.0f), 1e-5f);
  EXPECT_NEAR(ao.occlusion(scene.volume().world_box().lower), std::exp(-sigma * 5.0f / 8.0f), 1e-4f);
  const AmbientOcclusion half_density{table.view(), table.grid(), 5.0f, 0.5f};
  EXPECT_NEAR(half_density.occlusion(vec3(0.0f)), std::exp(-0.5f * sigma * 5.0f), 1e-5f);
}

Scene ao_spheres() {
  Scene scene = procedural_scene("spheres", ivec3(40), 40);
  scene.set_transfer_function(testing::step_tf(0.2f, vec3(0.9f, 0.7f, 0.5f), 0.3f));
  Light light;
  light.direction = glm::normalize(vec3(0.3f, 0.5f, -1.0f));
  scene.set_lights({light});
  Material m;
  m.ambient = 0.0f;
  scene.set_material(m);
  return scene;
}

// Occlusion has no direction: with isotropic scattering and no planes the
// image does not depend on where the light comes from, and a light move
// rebuilds nothing.
TEST(SatAo, OcclusionIgnoresTheLightDirection) {
  Scene scene = ao_spheres();
  const TechniqueInfo& info = find_technique("sat-ao");
  const ParameterValues params(info.parameters);
  auto t = info.create();
  t->prepare(scene, params);
  EXPECT_EQ(t->rebuilds(), 2u);  // table and cache
  Image before, after;
  t->render(scene, before);
  Light moved = scene.lights()[0];
  moved.direction = glm::normalize(vec3(-1.0f, 0.2f, 0.3f));
  scene.set_lights({moved});
  t->prepare(scene, params);
  EXPECT_EQ(t->rebuilds(), 2u);
  t->render(scene, after);
  EXPECT_LT(rmse(before, after), 1e-6);
}

// Occlusion darkens (against a zero density scale), and the cache stores the
// per-sample occlusion: with R = 8 voxels the occlusion varies slowly, so
// trilinear interpolation at the voxel grid is accurate to well under 1% of
// the image range. (A larger R is not simply darker: exp(-sigma_mean R) is
// exp(-mass / (8 R^2)), lighter once the cube outgrows the occluder.)
TEST(SatAo, OcclusionDarkensAndTheCacheMatchesDirectLookups) {
  const Scene scene = ao_spheres();
  const auto mean = [](const Image& image) { return luminance(testing::mean_rgb(image, 0, 0, 40, 40)); };
  const Image direct = render_with(scene, "sat-ao", {{"radius_voxels", 8.0}, {"shadow_cache", false}});
  const Image none = render_with(scene, "sat-ao", {{"shadow_density_scale", 0.0}});
  EXPECT_GT(mean(none), 1.1f * mean(direct));
  const Image cached = render_with(scene, "sat-ao", {{"radius_voxels", 8.0}, {"cache_resolution", 1.0}});
  EXPECT_LT(rmse(cached, direct), 0.005);
}

}  // namespace
}  // namespace penumbra

// convolution's automatic slab distance (Patel et al. 2013, section 7): with
// slab_distance unset, the meshes' detail sets it (half the finest lattice
// cell or texel in world units), the volume's render step bounds it where the
// volume has extinction, and an explicit slab_distance overrides both.
#include "penumbra/render/render_loop.h"
#include "penumbra/scene/mesh_shapes.h"
#include "penumbra/techniques/convolution/slab_renderer.h"
#include "penumbra/techniques/registry.h"
#include "test_scene.h"

#include <gtest/gtest.h>

#include <cmath>

namespace penumbra {
namespace {

using testing::procedural_scene;

// A sphere of radius 12 in a 32^3 frame (box [-15.5, 15.5]^3, voxel 1, render
// step 1) seen along -z by an orthographic camera: 31 world units of depth.
Scene detail_sphere_scene(DetailFunction detail, bool volume_has_medium) {
  Scene scene = procedural_scene("empty", ivec3(32), 16);
  TransferFunction clear({{0.0f, vec3(1.0f), volume_has_medium ? 0.05f : 0.0f}, {1.0f, vec3(1.0f), 0.05f}});
  if (!volume_has_medium) clear = TransferFunction({{0.0f, vec3(1.0f), 0.0f}, {1.0f, vec3(1.0f), 0.0f}});
  scene.set_transfer_function(clear);
  RenderSettings render = scene.render();
  render.step = 1.0f;
  scene.set_render(render);
  scene.set_camera(testing::orthographic_camera(vec3(0.0f, 0.0f, 100.0f), 32.0f));
  MeshObject m;
  m.source.builtin = "sphere";
  m.mesh = make_builtin_mesh("sphere", 2);
  m.scale = vec3(12.0f);
  m.material.detail = detail;
  m.material.specular = 0.0f;
  scene.set_meshes({m});
  return scene;
}

int slab_count(const Scene& scene, const ParameterSettings& params = {}) {
  RenderStats stats;
  testing::render_with(scene, "convolution", params, &stats);
  return int(stats.passes);
}

DetailFunction noise(float frequency) {
  DetailFunction d;
  d.type = DetailType::Noise;
  d.frequency = frequency;
  return d;
}

// Depth 31 (the box's; the meshes lie inside it) over e, rounded up.
int expected_slabs(float e) { return int(std::ceil(31.0f / e)); }

TEST(ConvolutionSlabCount, FollowsTheDetailsFinestFeature) {
  // Noise at frequency 2 on a radius-12 sphere: cells of 6 world units, e = 3.
  EXPECT_EQ(slab_count(detail_sphere_scene(noise(2.0f), false)), expected_slabs(3.0f));
  // Twice the frequency, half the distance.
  EXPECT_EQ(slab_count(detail_sphere_scene(noise(4.0f), false)), expected_slabs(1.5f));
  // fBm: its third octave at lacunarity 2 is 4x the base frequency.
  DetailFunction fbm = noise(1.0f);
  fbm.type = DetailType::Fbm;
  fbm.fractal.octaves = 3;
  EXPECT_EQ(slab_count(detail_sphere_scene(fbm, false)), expected_slabs(12.0f / 4.0f / 2.0f));
  // A 9^3 texture over the sphere's object bounds [-1, 1]^3: texels 0.25
  // object units apart, 3 world units; e = 1.5.
  auto texture = std::make_shared<Volume>(ivec3(9), VoxelType::Float32);
  DetailFunction tex;
  tex.type = DetailType::Texture;
  tex.texture = texture;
  tex.texture_file = "test.nrrd";
  EXPECT_EQ(slab_count(detail_sphere_scene(tex, false)), expected_slabs(1.5f));
}

TEST(ConvolutionSlabCount, RenderStepBoundsItAndAnExplicitDistanceWins) {
  // Constant detail asks for nothing: the render step (1 voxel).
  DetailFunction constant;
  constant.type = DetailType::Constant;
  EXPECT_EQ(slab_count(detail_sphere_scene(constant, false)), expected_slabs(1.0f));
  // Coarse detail over a volume with extinction: the step still samples the volume.
  EXPECT_EQ(slab_count(detail_sphere_scene(noise(0.5f), true)), expected_slabs(1.0f));
  EXPECT_EQ(slab_count(detail_sphere_scene(noise(0.5f), false)), expected_slabs(12.0f));
  // Fine detail over it: the detail.
  EXPECT_EQ(slab_count(detail_sphere_scene(noise(12.0f), true)), expected_slabs(0.5f));
  EXPECT_EQ(slab_count(detail_sphere_scene(noise(12.0f), true), {{"slab_distance", 2.0}}), expected_slabs(2.0f));
  // Detail too fine for the cap: at most kAutomaticSlabs slabs.
  EXPECT_NEAR(slab_count(detail_sphere_scene(noise(1e5f), false)), SlabRenderer::kAutomaticSlabs, 1);
}

// A light at angle theta to the view drifts e tan(theta) sideways per slab:
// the automatic distance keeps that within a voxel (1 here), taking at most
// kMaxDriftRefinement times the slabs the step and the detail give.
TEST(ConvolutionSlabCount, ObliqueLightsTakeThinnerSlabs) {
  DetailFunction constant;
  constant.type = DetailType::Constant;
  const auto lit = [](Scene scene, float tan) {
    scene.set_lights({testing::directional_light(glm::normalize(vec3(tan, 0.0f, -1.0f)))});
    return scene;
  };
  const Scene stepped = detail_sphere_scene(constant, false);  // e = the step, 1
  EXPECT_EQ(slab_count(lit(stepped, 0.0f)), expected_slabs(1.0f));
  EXPECT_EQ(slab_count(lit(stepped, 0.9f)), expected_slabs(1.0f));  // drifts 0.9 a slab
  EXPECT_NEAR(slab_count(lit(stepped, 2.0f)), expected_slabs(0.5f), 1);
  EXPECT_NEAR(slab_count(lit(stepped, 3.0f)), expected_slabs(1.0f / 3.0f), 1);
  EXPECT_NEAR(slab_count(lit(stepped, 10.0f)), expected_slabs(0.25f), 1);  // at most 4x the slabs
  // Coarse detail (e = 12): a light at tan 0.5 drifts 6 a slab; 2 would keep it
  // within a voxel, 3 is the most slabs allowed.
  EXPECT_NEAR(slab_count(lit(detail_sphere_scene(noise(0.5f), false), 0.5f)), expected_slabs(3.0f), 1);
  // An explicit distance is kept.
  EXPECT_EQ(slab_count(lit(stepped, 3.0f), {{"slab_distance", 1.0}}), expected_slabs(1.0f));
}

}  // namespace
}  // namespace penumbra

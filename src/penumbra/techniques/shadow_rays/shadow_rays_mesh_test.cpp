// shadow-rays draws the scene's meshes (issue 23): their media along the
// viewing rays and along every shadow ray (render/mesh_march.h,
// mesh_transmittance), checked against closed-form chords, Beer-Lambert on
// the floor, and the path tracer's single scattering.
#include "penumbra/techniques/registry.h"
#include "mesh_test_scenes.h"
#include "test_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace penumbra {
namespace {

using testing::chord;
using testing::compare_box;
using testing::dense_box_scene;
using testing::homogeneous_sphere;
using testing::mesh_scene;
using testing::pixel_world;
using testing::render_with;

const ParameterSettings kSingleScattering{{"spp", 256.0}, {"mode", std::string("single")}, {"progress", false}};

// The pixel's opacity is 1 - exp(-optical depth) through the nested spheres:
// the pieces of a viewing ray end at the exact crossings, so a homogeneous
// medium integrates exactly whatever the step; what is left is the
// tessellation, largest where a pixel's ray grazes the inner sphere's rim
// (measured 0.0075, the same with jitter).
TEST(ShadowRaysMeshes, NestedSpheresFollowBeerLambert) {
  constexpr int kImage = 48;
  constexpr float kHeight = 32.0f;
  Scene scene = mesh_scene(kImage, kHeight, 1.0f);
  scene.set_meshes({homogeneous_sphere(12.0f, vec3(0.0f)), homogeneous_sphere(5.0f, vec3(2.0f, 1.0f, 0.0f), 0.3f)});
  for (const bool jitter : {false, true}) {
    RenderSettings r = scene.render();
    r.jitter = jitter;
    scene.set_render(r);
    const Image image = render_with(scene, "shadow-rays");
    const float sigma = -std::log(1.0f - testing::kMeshAlphaPerUnit), sigma_inner = -std::log(1.0f - 0.3f);
    float worst = 0.0f;
    for (int y = 0; y < kImage; ++y) {
      for (int x = 0; x < kImage; ++x) {
        const vec2 p = pixel_world(x, y, kImage, kHeight);
        if (glm::length(p) > 0.9f * 12.0f) continue;  // the rim, where the chord is steep in r
        const float depth = sigma * chord(12.0f, p) + sigma_inner * chord(5.0f, p - vec2(2.0f, 1.0f));
        worst = std::max(worst, std::abs(image.at(x, y).a - (1.0f - std::exp(-depth))));
      }
    }
    std::printf("shadow-rays nested spheres, jitter %d: worst alpha error %.5f\n", int(jitter), worst);
    EXPECT_LT(worst, 0.015f) << "jitter " << jitter;
  }
}

// The floor under a mesh sphere gets lit * exp(-sigma chord) along each
// light ray: the shadow ray's pieces inside the mesh are exact chords too.
// With the shadow cache as well: it holds the volume's transmittance, and
// the mesh's is marched per lookup. Measured: worst 0.0002 in the core (the
// tessellation), 0 outside.
TEST(ShadowRaysMeshes, ShadowOnTheFloorFollowsBeerLambert) {
  for (const bool cache : {false, true}) {
    const testing::FloorShadow f = testing::sphere_floor_shadow(
        "shadow-rays", {{"shadow_cache", cache}}, cache ? "shadow_rays_mesh_shadow_cached.png" : "shadow_rays_mesh_shadow.png");
    EXPECT_GT(f.inside, 20);
    EXPECT_LT(f.worst_inside, 0.001f) << "shadow_cache " << cache;
    EXPECT_LT(f.worst_outside, 1e-4f) << "shadow_cache " << cache;
  }
}

// The dense box (sigma 4.6 per unit) as a mesh against the path tracer's
// single scattering on the same mesh (256 paths per pixel: standard error of
// the interior mean about 0.001). Measured 0.4208 against 0.4223; with steps
// of a fixed optical depth of 0.25 instead of 0.1 (kMeshStepDepth) 0.4179, and
// at the render step 0.24 (which shadow-rays' volume box, marched at the
// render step, still gives: printed).
TEST(ShadowRaysMeshes, DenseMeshBoxMatchesPathtraceSingleScattering) {
  const Scene mesh_box = dense_box_scene(true), volume_box = dense_box_scene(false);
  const Image traced = render_with(mesh_box, "pathtrace", kSingleScattering);
  const Image mesh = render_with(mesh_box, "shadow-rays");
  const Image volume = render_with(volume_box, "shadow-rays");
  testing::save_test_image(mesh, "shadow_rays_dense_box_mesh.png");
  const testing::BoxComparison against_paths = compare_box(mesh, traced);
  const testing::BoxComparison against_volume = compare_box(mesh, volume);
  std::printf("dense box: shadow-rays mesh %.4f, path-traced mesh %.4f (rms %.4f), shadow-rays volume %.4f\n",
              against_paths.mean_mesh, against_paths.mean_volume, against_paths.rms_difference,
              against_volume.mean_volume);
  EXPECT_NEAR(against_paths.mean_mesh, against_paths.mean_volume, 0.005f);
}

// A mesh sphere filled with fBm detail overlapping the volume's spheres,
// with a floor: volume and mesh media along the same rays, both casting
// shadows onto each other and the floor, against the path tracer's single
// scattering (256 paths per pixel). Measured: bias -0.00011 (the path
// tracer's own standard error of the mean is about 0.0001), rms 0.0043 (its
// per-pixel noise).
Scene fbm_sphere_in_volume(int image) {
  Scene scene = testing::procedural_scene("spheres", ivec3(32), image);
  TransferFunction tf({{0.0f, vec3(1.0f, 0.7f, 0.4f), 0.0f}, {1.0f, vec3(1.0f, 0.7f, 0.4f), 0.8f}});
  tf.set_range(vec2(0.0f, 1.0f));
  scene.set_transfer_function(tf);
  MeshObject sphere = homogeneous_sphere(8.0f, vec3(0.0f, -1.0f, 4.0f));
  sphere.material.detail.type = DetailType::Fbm;
  sphere.material.detail.frequency = 2.5f;
  TransferFunction mesh_tf({{-1.0f, vec3(0.5f, 0.8f, 1.0f), 0.0f}, {1.0f, vec3(0.5f, 0.8f, 1.0f), 0.25f}});
  mesh_tf.set_unit_length(1.0f);
  sphere.material.tf = mesh_tf;
  scene.set_meshes({sphere});
  Camera cam;
  cam.eye = vec3(30.0f, -70.0f, 45.0f);
  cam.target = vec3(0.0f, 0.0f, -5.0f);
  cam.up = vec3(0.0f, 0.0f, 1.0f);
  cam.fov_deg = 40.0f;
  scene.set_camera(cam);
  Light light;
  light.direction = glm::normalize(vec3(0.6f, -0.4f, -1.0f));
  scene.set_lights({light});
  Material m;
  m.ambient = 0.0f;
  scene.set_material(m);
  scene.set_planes({Plane{vec3(0.0f, 0.0f, -20.0f), vec3(0.0f, 0.0f, 1.0f), vec3(0.8f)}});
  return scene;
}

TEST(ShadowRaysMeshes, MeshInAVolumeMatchesPathtraceSingleScattering) {
  const Scene scene = fbm_sphere_in_volume(32);
  const Image traced = render_with(scene, "pathtrace", kSingleScattering);
  const Image rays = render_with(scene, "shadow-rays");
  testing::save_test_image(rays, "shadow_rays_fbm_sphere_in_volume.png");
  testing::save_test_image(traced, "pathtrace_fbm_sphere_in_volume.png");
  double signed_sum = 0.0, squared = 0.0;
  for (int y = 0; y < rays.height(); ++y) {
    for (int x = 0; x < rays.width(); ++x) {
      const vec4 d = rays.at(x, y) - traced.at(x, y);
      const double g = (double(d.r) + d.g + d.b) / 3.0;
      signed_sum += g;
      squared += g * g;
    }
  }
  const double n = double(rays.width()) * rays.height();
  const double bias = signed_sum / n, rms = std::sqrt(squared / n);
  std::printf("fBm sphere in the volume: shadow-rays minus pathtrace: bias %.5f, rms %.5f\n", bias, rms);
  EXPECT_LT(std::abs(bias), 0.0006);
  EXPECT_LT(rms, 0.008);
}

// A mesh scene draws its meshes (the technique says so).
TEST(ShadowRaysMeshes, SaysItDrawsMeshes) { EXPECT_TRUE(find_technique("shadow-rays").draws_meshes); }

}  // namespace
}  // namespace penumbra

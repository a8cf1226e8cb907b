// ambient-scattering: the tube through a homogeneous slab against its closed
// form, softness growing with the radius, the radius from the light's size,
// the cache against the tube march, what rebuilds when, bad parameters.
#include "penumbra/analysis/image_metrics.h"
#include "penumbra/base/error.h"
#include "penumbra/techniques/ambient_scattering/ambient_tube.h"
#include "penumbra/techniques/filtered_sat/shadow_filter.h"
#include "penumbra/techniques/registry.h"
#include "penumbra/techniques/sat_common/volume_aligned_table.h"
#include "penumbra_edge.h"
#include "test_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace penumbra {
namespace {

using testing::procedural_scene;
using testing::render_with;

// The slab's tube in closed form: light along +z from p, spheres of radius
// R at p + 2kR, each holding the fraction of its cube (half-width R) below
// the slab's top face; a sphere whose near side lies past the light
// (distance) or past the grown box ends the tube. With albedo 0 a sphere
// passes on e^(-2 tau_k) and the sample's own sphere (inside) e^(-tau_0):
// a box filter of width 2R along the light.
double slab_visibility(double sigma, double radius, double p_z, double top, double distance) {
  const double h = radius;
  double depth = sigma * radius;
  for (int k = 1;; ++k) {
    const double centre = p_z + 2.0 * k * radius;
    if (2.0 * k * radius - radius >= std::min(distance, top + h - p_z)) break;
    const double inside = std::clamp((top - (centre - h)) / (2.0 * h), 0.0, 1.0);
    depth += 2.0 * radius * sigma * inside;
  }
  return std::exp(-depth);
}

TEST(AmbientScattering, HomogeneousSlabFollowsTheTubesClosedForm) {
  Scene scene = procedural_scene("slab", ivec3(48), 8);
  scene.set_transfer_function(testing::step_tf(0.0f, vec3(1.0f), 0.2f));
  SceneResources resources;
  resources.update(scene);
  VolumeAlignedTable table("test");
  ASSERT_TRUE(table.update(scene, resources, 1.0));
  const ScatteringTable black(ScatteringModel{0.0f, 0.0f, 16});
  const Box3 box = scene.volume().world_box();
  const double sigma = -std::log(0.8);
  for (const float radius : {1.5f, 2.5f, 4.0f}) {
    AmbientTube tube{table.view(), table.grid(), box, radius, 1.0f, black.view(), CameraView{}};
    const vec3 p(1.0f, -2.0f, -15.25f);
    LightSample ls{vec3(0.0f, 0.0f, 1.0f), kInfinity, vec3(1.0f)};
    const double directional = slab_visibility(sigma, radius, p.z, box.upper.z, 1e30);
    EXPECT_NEAR(tube.sample_visibility(p, ls), directional, 2e-4 * directional) << "radius " << radius;
    ls.distance = 17.0f;  // a point light inside the slab
    const double point = slab_visibility(sigma, radius, p.z, box.upper.z, 17.0);
    EXPECT_NEAR(tube.sample_visibility(p, ls), point, 2e-4 * point) << "radius " << radius;
    EXPECT_GT(point, directional);
    // A surface's own sphere takes H = e^-tau_0 without albedo.
    EXPECT_NEAR(tube.surface_visibility(p, ls), point, 2e-4 * point);
  }
  // Scattering inside the spheres passes more light on, and the view
  // lookup follows the phase function's lobe: forward-scattering spheres
  // send more toward a viewer looking into the light.
  const ScatteringTable white(ScatteringModel{0.8f, 0.6f, 256});
  AmbientTube tube{table.view(), table.grid(), box, 2.5f, 1.0f, white.view(), CameraView{}};
  const vec3 p(0.0f, 0.0f, 10.0f);
  const LightSample ls{vec3(0.0f, 0.0f, 1.0f), kInfinity, vec3(1.0f)};
  const double black_visibility = slab_visibility(sigma, 2.5, p.z, box.upper.z, 1e30);
  tube.camera.eye = vec3(0.0f, 0.0f, 60.0f);  // looking down, against the light: mu = -1
  const float against = tube.sample_visibility(p, ls);
  tube.camera.eye = vec3(0.0f, 0.0f, -60.0f);  // looking up, with the light: mu = 1
  const float along = tube.sample_visibility(p, ls);
  std::printf("slab: albedo 0 %.4f, albedo 0.8 g 0.6 along the light %.4f, against %.4f\n", black_visibility, along,
              against);
  EXPECT_GT(along, 1.2 * black_visibility);
  // Over the phase function: the forward lobe is mostly the direct beam's,
  // so the ratio grows where the phase function is small.
  EXPECT_GT(against, along);
}

// The sharp edge of penumbra_edge.h: the floor's 10-90 % penumbra grows
// with the ambient radius, in proportion once the cube (2R) is much wider
// than the edge's one-voxel interpolation ramp (measured 1.73, 2.56, 5.04
// world units at R = 2, 4, 8).
TEST(AmbientScattering, ShadowsSoftenAsTheRadiusGrows) {
  const testing::EdgeScene edge = testing::edge_scene(Light{}, 40.0f, 96, 48.0f);
  const Image unshadowed = testing::unshadowed_floor(edge);
  float previous = 0.0f;
  std::vector<float> widths;
  for (const double radius : {2.0, 4.0, 8.0}) {
    const Image image = render_with(edge.scene, "ambient-scattering",
                                    {{"radius_voxels", radius}, {"scattering_albedo", 0.0}, {"shadow_cache", false},
                                     {"sat_resolution", 1.0}});
    const float width = testing::penumbra_width_10_90(edge, image, unshadowed);
    std::printf("radius %.0f voxels: penumbra %.3f\n", radius, width);
    EXPECT_GT(width, 1.3f * previous);
    previous = width;
    widths.push_back(width);
  }
  EXPECT_NEAR(widths[2] / widths[1], 2.0f, 0.2f);
}

// radius_voxels unset follows the light's size: a distant light gives the
// radius whose cube is as wide as filtered-sat's derived filter; a
// directional light 8 voxels; an explicit radius overrides both.
TEST(AmbientScattering, RadiusFollowsTheLightsSize) {
  Scene scene = testing::with_floor(testing::lit_spheres(32));
  const Light sized = testing::as_distant(scene.lights()[0], 6.0f);
  const float width = filter_from_light(sized, scene.volume().world_box()).width;
  const double matching = 0.5 * width;
  testing::expect_knob_overrides_light(scene, "ambient-scattering", {{"shadow_cache", false}}, "radius_voxels", sized,
                                       matching, scene.lights()[0], 8.0, 3.0);
}

Scene spheres_and_two_lights() {
  Scene scene = testing::lit_spheres(40);
  scene.set_lights({scene.lights()[0], testing::point_light(vec3(20.0f, -30.0f, 45.0f))});
  return scene;
}

// The cache (tube transfer and optical radius on the data grid, the view
// lookup per sample) against the tube marched per sample.
TEST(AmbientScattering, CacheMatchesTheTubeMarch) {
  const Scene scene = testing::with_floor(spheres_and_two_lights());
  const Image direct = render_with(scene, "ambient-scattering", {{"shadow_cache", false}});
  const Image cached = render_with(scene, "ambient-scattering", {{"cache_resolution", 1.0}});
  const double error = rmse(cached, direct);
  std::printf("cache at the data grid vs tube march: rmse %.5f\n", error);
  EXPECT_LT(error, 0.004);
  // Scattering inside the spheres only adds light: nowhere darker than
  // extinction alone, brighter on average.
  const Image black = render_with(scene, "ambient-scattering", {{"scattering_albedo", 0.0}, {"shadow_cache", false}});
  for (int y = 0; y < direct.height(); ++y) {
    for (int x = 0; x < direct.width(); ++x) ASSERT_GE(direct.at(x, y).r, black.at(x, y).r - 1e-5f) << x << ", " << y;
  }
  const float lit = luminance(testing::mean_rgb(direct, 0, 0, 40, 40));
  const float unlit = luminance(testing::mean_rgb(black, 0, 0, 40, 40));
  std::printf("mean luminance: albedo 0.6 %.4f, 0 %.4f\n", lit, unlit);
  EXPECT_GT(lit, 1.015f * unlit);
}

// Only what a structure depends on rebuilds it: the SAT on data, extinction
// and clip planes; the optical-radius grid with it and on the radius; a
// light's tube cache when that light moves; nothing for a colour, an
// intensity, a floor, a render-only TF edit or the camera.
TEST(AmbientScattering, OnlyWhatAStructureDependsOnRebuildsIt) {
  Scene scene = spheres_and_two_lights();
  scene.set_shadow_transfer_function(scene.transfer_function());
  const TechniqueInfo& info = find_technique("ambient-scattering");
  ParameterValues params(info.parameters);
  auto t = info.create();
  t->prepare(scene, params);
  const std::uint64_t all = 4;  // SAT, optical radii, two tubes
  EXPECT_EQ(t->rebuilds(), all);
  std::uint64_t count = t->rebuilds();
  std::vector<Light> lights = scene.lights();
  lights[0].color = vec3(0.2f, 0.5f, 1.0f);
  lights[1].intensity = 900.0f;
  scene.set_lights(lights);
  scene.set_planes({Plane{vec3(0.0f, 0.0f, -30.0f), vec3(0.0f, 0.0f, 1.0f), vec3(0.8f)}});
  TransferFunction render_only = scene.transfer_function();
  render_only.set_density_scale(0.5f);
  scene.set_transfer_function(render_only);
  Camera camera = scene.camera();
  camera.orbit(30.0f, 10.0f);
  scene.set_camera(camera);
  t->prepare(scene, params);
  EXPECT_EQ(t->rebuilds(), count) << "colour, intensity, floor, camera or render TF rebuilt something";
  lights[0].direction = glm::normalize(vec3(-0.4f, 0.7f, -1.0f));
  scene.set_lights(lights);
  t->prepare(scene, params);
  EXPECT_EQ(t->rebuilds(), count += 1) << "a light's direction: its tube";
  lights[1].position += vec3(5.0f, 0.0f, 0.0f);
  scene.set_lights(lights);
  t->prepare(scene, params);
  EXPECT_EQ(t->rebuilds(), count += 1) << "a light's position: its tube";
  TransferFunction shadow = *scene.shadow_transfer_function();
  shadow.set_density_scale(2.0f);
  scene.set_shadow_transfer_function(shadow);
  t->prepare(scene, params);
  EXPECT_EQ(t->rebuilds(), count += all) << "shadow extinction";
  scene.set_clip_planes({vec4(0.0f, 0.0f, 1.0f, 5.0f)});
  t->prepare(scene, params);
  EXPECT_EQ(t->rebuilds(), count += all) << "clip plane";
  scene.set_volume(make_procedural_volume("marschner-lobb", ivec3(40)));
  t->prepare(scene, params);
  EXPECT_EQ(t->rebuilds(), count += all) << "data";
  params.set("radius_voxels", 5.0);
  t->prepare(scene, params);
  EXPECT_EQ(t->rebuilds(), count += all - 1) << "radius: the caches, not the SAT";
  params.set("scattering_albedo", 0.3);
  t->prepare(scene, params);
  EXPECT_EQ(t->rebuilds(), count += all - 1) << "albedo: the caches, not the SAT";
  Material m = scene.material();
  m.ambient = 0.3f;
  scene.set_material(m);
  t->prepare(scene, params);
  EXPECT_EQ(t->rebuilds(), count) << "ambient";
}

TEST(AmbientScattering, BadParametersNameTheParameter) {
  const TechniqueInfo& info = find_technique("ambient-scattering");
  ParameterValues params(info.parameters);
  for (const auto& [name, value] : std::vector<std::pair<std::string, double>>{
           {"scattering_albedo", 0.99}, {"scattering_albedo", -0.1}, {"radius_voxels", 100.0},
           {"preintegration_paths", 0.0}, {"sat_resolution", 0.0}}) {
    try {
      params.set(name, value);
      ADD_FAILURE() << name << " = " << value << " accepted";
    } catch (const InvalidArgument& e) {
      EXPECT_EQ(e.name(), name);
    }
  }
  params.set("radius_voxels", 0.25);  // in the declared range, below half a voxel
  auto t = info.create();
  try {
    t->prepare(testing::lit_spheres(16), params);
    ADD_FAILURE() << "radius 0.25 accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.name(), "radius_voxels");
  }
}

}  // namespace
}  // namespace penumbra

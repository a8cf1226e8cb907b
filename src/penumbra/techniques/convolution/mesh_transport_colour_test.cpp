// Chromatic attenuation through a mesh's transport colour (Patel et al.
// 2013, Fig. 7e; scene key meshes[i].material.transport_color): light that
// crosses the medium attenuates per channel with sigma_t (1 - transport
// colour), so a sphere that lets red through casts a red shadow. Checked
// against Beer-Lambert per channel in convolution (three light buffers per
// light), shadow-rays and the path tracer, which must agree.
#include "penumbra/techniques/registry.h"
#include "mesh_test_scenes.h"
#include "test_scene.h"

#include <gtest/gtest.h>

#include <cmath>

namespace penumbra {
namespace {

using testing::FloorShadow;
using testing::sphere_floor_shadow;

const vec3 kRed(0.8f, 0.2f, 0.1f);  // lets red through: light extinction 0.2 / 0.8 / 0.9 sigma

// The floor under a sphere of transport colour kRed is red in each technique
// that draws meshes, per channel within the bounds of their grey shadow
// tests (the path tracer's noise, shadow-rays' tessellation; convolution's
// blur error s^2 T'' / 2 is largest in red, the brightest channel of the
// core: measured 0.0155 there against 0.0122 grey, hence 0.02), and the
// three agree on the core's colour (measured: convolution 0.3501 / 0.0836 /
// 0.0660, shadow-rays 0.3528 / 0.0857 / 0.0677, pathtrace 0.3535 / 0.0864 /
// 0.0683, whose core mean has a standard error of about 0.0014).
TEST(MeshTransportColour, RedMediumTintsTheFloorRed) {
  const FloorShadow conv = sphere_floor_shadow("convolution", {}, "conv_mesh_shadow_red.png", kRed);
  const FloorShadow rays = sphere_floor_shadow("shadow-rays", {}, "shadow_rays_mesh_shadow_red.png", kRed);
  const FloorShadow paths = sphere_floor_shadow("pathtrace", {{"spp", 1024.0}, {"progress", false}},
                                                "pathtrace_mesh_shadow_red.png", kRed);
  for (const FloorShadow* f : {&conv, &rays, &paths}) {
    EXPECT_GT(f->inside, 20);
    EXPECT_GT(f->core.r, 3.0f * f->core.g);  // red: the chord's light depth is 0.2 sigma in red, 0.8 in green
    EXPECT_GT(f->core.g, f->core.b);
  }
  EXPECT_LT(conv.worst_inside, 0.02f);
  EXPECT_LT(conv.worst_outside, 0.005f);
  EXPECT_LT(rays.worst_inside, 0.001f);
  EXPECT_LT(rays.worst_outside, 1e-4f);
  EXPECT_LT(paths.worst_inside, 0.04f);
  EXPECT_LT(std::abs(paths.mean_inside), 0.005);
  EXPECT_LT(paths.worst_outside, 1e-4f);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(conv.core[c], paths.core[c], 0.01f) << "channel " << c;
    EXPECT_NEAR(rays.core[c], paths.core[c], 0.005f) << "channel " << c;
  }
}

// Grey scenes cost nothing extra: one light buffer pair per light unless a
// mesh asks for a transport colour (then three); a transport colour of
// black attenuates exactly like none.
TEST(MeshTransportColour, OnlyAMaterialThatAsksGetsColourBuffers) {
  Scene scene = testing::mesh_scene(32, 64.0f, 0.0f);
  MeshObject sphere = testing::homogeneous_sphere(12.0f, vec3(0.0f), 0.3f);
  Light light;
  light.direction = glm::normalize(vec3(1.0f, 0.0f, -1.0f));
  scene.set_lights({light});
  scene.set_planes({Plane{vec3(0.0f, 0.0f, -20.0f), vec3(0.0f, 0.0f, 1.0f), vec3(0.8f)}});
  const TechniqueInfo& info = find_technique("convolution");
  auto render = [&](std::optional<vec3> transport, std::uint64_t& bytes) {
    sphere.material.transport_color = transport;
    scene.set_meshes({sphere});
    auto t = info.create();
    t->prepare(scene, ParameterValues(info.parameters));
    Image image;
    t->render(scene, image);
    bytes = t->aux_bytes();
    return image;
  };
  std::uint64_t grey_bytes = 0, black_bytes = 0;
  const Image grey = render(std::nullopt, grey_bytes);
  const Image black = render(vec3(0.0f), black_bytes);
  const std::uint64_t pixels = 32 * 32;  // at least: the guard band adds some
  EXPECT_GE(black_bytes - grey_bytes, 2 * 2 * pixels * sizeof(float));  // two more channels, ping-pong
  float worst = 0.0f;
  for (int y = 0; y < 32; ++y) {
    for (int x = 0; x < 32; ++x) worst = std::max(worst, glm::length(black.at(x, y) - grey.at(x, y)));
  }
  EXPECT_LT(worst, 1e-6f);
}

}  // namespace
}  // namespace penumbra

// The three shadow maps (shadow-map, deep-shadow-map, cssm) as techniques:
// agreement with shadow-rays on an opaque occluder, grey and coloured
// shadows on a floor, the separate shadow TF, several lights, and what
// triggers a rebuild.
#include "penumbra/analysis/image_metrics.h"
#include "penumbra/base/error.h"
#include "penumbra/base/memory_budget.h"
#include "penumbra/techniques/registry.h"
#include "test_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

namespace penumbra {
namespace {

using testing::procedural_scene;

// Renders with 256^2 maps (unless `params` says otherwise), which resolve
// these 32^3 volumes finely (a texel is about 0.2 voxel) and keep tests fast.
Image render_with(const Scene& scene, const std::string& technique, ParameterSettings params = {}) {
  if (find_technique(technique).parameters.find("resolution")) params.emplace("resolution", 256.0);
  return testing::render_with(scene, technique, params);
}

const char* const kShadowMaps[] = {"shadow-map", "deep-shadow-map", "cssm"};

// A scene seen straight from above with an orthographic camera, a floor
// below the volume and no ambient light, so a floor pixel is
// cos(light) * V(floor point) * plane colour.
Scene floor_scene(const std::string& builtin, const TransferFunction& tf, const Light& light) {
  Scene scene = procedural_scene(builtin, ivec3(32), 48);
  scene.set_transfer_function(tf);
  scene.set_lights({light});
  Material m;
  m.ambient = 0.0f;
  scene.set_material(m);
  scene.set_planes({Plane{vec3(0.0f, 0.0f, -36.0f), vec3(0.0f, 0.0f, 1.0f), vec3(1.0f)}});
  Camera camera;
  camera.eye = vec3(16.0f, 0.0f, 200.0f);
  camera.target = vec3(16.0f, 0.0f, 0.0f);
  camera.up = vec3(0.0f, 1.0f, 0.0f);
  camera.projection = Projection::Orthographic;
  camera.ortho_height = 110.0f;
  scene.set_camera(camera);
  return scene;
}

Light slanted_directional() {
  Light light;
  light.direction = glm::normalize(vec3(1.0f, 0.2f, -1.0f));
  return light;
}

Light point_light() {
  Light light;
  light.type = LightType::Point;
  light.position = vec3(-30.0f, 5.0f, 60.0f);
  light.intensity = 4500.0f;
  return light;
}

// Fraction of pixels whose colour differs by more than `threshold`.
double fraction_differing(const Image& a, const Image& b, float threshold) {
  int n = 0;
  for (std::size_t i = 0; i < a.pixel_count(); ++i) {
    n += max_component(glm::abs(vec3(a.data()[i]) - vec3(b.data()[i]))) > threshold;
  }
  return double(n) / double(a.pixel_count());
}

// A black opaque half-plane (the `edge` volume) over a floor: shadow-rays
// gives T = 0 behind it and 1 elsewhere; every shadow map must agree except
// along the shadow's edge, where the map's texels, the voxel ramp of the
// occluder's border and the CSSM's offsets put the boundary up to about one
// floor pixel apart: at most 4% of the pixels (the edge is ~1 pixel wide
// across a 48-pixel image) and a small mean error.
TEST(ShadowMapRelations, AllAgreeWithShadowRaysOnAnOpaqueOccluder) {
  for (const Light& light : {slanted_directional(), point_light()}) {
    const Scene scene = floor_scene("edge", testing::step_tf(0.5f, vec3(0.0f), 1.0f), light);
    const Image reference = render_with(scene, "shadow-rays");
    for (const char* name : kShadowMaps) {
      SCOPED_TRACE(std::string(name) + (light.type == LightType::Point ? " point" : " directional"));
      const Image image = render_with(scene, name);
      std::printf("[shadow maps] opaque edge, %s, %s light: %.4f of pixels differ, mean error %.5f\n", name,
                  light.type == LightType::Point ? "point" : "directional", fraction_differing(image, reference, 0.05f),
                  mean_absolute_error(image, reference));
      EXPECT_LT(fraction_differing(image, reference, 0.05f), 0.04);
      EXPECT_LT(mean_absolute_error(image, reference), 0.01);
    }
  }
}

// A grey translucent occluder: every pixel stays grey (the visibility is the
// same in every channel), and its shadow is partial.
TEST(ShadowMapRelations, GreyOccluderGivesGreyShadows) {
  const Scene scene = floor_scene("spheres", testing::step_tf(0.3f, vec3(0.25f), 0.3f), slanted_directional());
  const Image unshadowed = render_with(scene, "shadow-rays", {{"shadow_density_scale", 0.0}});
  for (const char* name : kShadowMaps) {
    SCOPED_TRACE(name);
    const Image image = render_with(scene, name);
    for (const vec4& p : image.pixels()) {
      ASSERT_NEAR(p.r, p.g, 1e-5f);
      ASSERT_NEAR(p.g, p.b, 1e-5f);
    }
    std::printf("[shadow maps] grey occluder, %s: largest darkening %.3f\n", name, max_abs_error(image, unshadowed));
    EXPECT_GT(max_abs_error(image, unshadowed), 0.2) << "no shadow";
  }
}

// A red translucent shell around an opaque core over a floor. In the shell's
// partial shadow (the floor pixels where shadow-rays' grey transmittance is
// between 0.15 and 0.85) the coloured techniques transmit red and absorb
// green: red / green > 2 there; the plain shadow map and the uncoloured
// variants stay grey.
TEST(ShadowMapRelations, RedTranslucentShellTintsTheFloorShadow) {
  TransferFunction tf({{0.0f, vec3(1.0f), 0.0f},
                       {0.4f, vec3(1.0f, 0.1f, 0.1f), 0.0f},
                       {0.45f, vec3(1.0f, 0.1f, 0.1f), 0.12f},
                       {0.6f, vec3(1.0f, 0.1f, 0.1f), 0.12f},
                       {0.65f, vec3(0.5f), 0.0f},
                       {0.9f, vec3(0.5f), 0.0f},
                       {0.95f, vec3(0.5f), 1.0f}});
  tf.set_range(vec2(0.0f, 1.0f));
  const Light light = slanted_directional();
  const Scene scene = floor_scene("shell", tf, light);
  const Image reference = render_with(scene, "shadow-rays");
  const float lit = std::abs(light.direction.z);  // cos of the floor's incidence angle
  const CameraView view = scene.camera().view();
  const Box3 box = scene.volume().world_box();
  std::vector<int> shell_shadow;
  for (int y = 0; y < 48; ++y) {
    for (int x = 0; x < 48; ++x) {
      const Ray ray = view.pixel_ray(float(x) + 0.5f, float(y) + 0.5f, 48, 48);
      if (!intersect_box(ray, box, 0.0f, kInfinity).empty()) continue;  // the volume hides the floor
      const float v = reference.at(x, y).r / lit;
      if (v > 0.15f && v < 0.85f) shell_shadow.push_back(y * 48 + x);
    }
  }
  ASSERT_GT(shell_shadow.size(), 20u);
  auto mean_rgb = [&](const Image& image) {
    vec3 sum(0.0f);
    for (int i : shell_shadow) sum += vec3(image.data()[i]);
    return sum / float(shell_shadow.size());
  };
  for (const char* name : {"deep-shadow-map", "cssm"}) {
    const vec3 coloured = mean_rgb(render_with(scene, name));
    std::printf("[shadow maps] red shell, %s: shadow rgb %.3f %.3f %.3f (unshadowed %.3f) over %zu pixels\n", name,
                coloured.r, coloured.g, coloured.b, lit, shell_shadow.size());
    EXPECT_GT(coloured.r, 2.0f * coloured.g) << name;
    EXPECT_GT(coloured.r, 0.8f * lit) << name << ": red passes the red shell";
    const vec3 grey = mean_rgb(render_with(scene, name, {{"colored", false}}));
    EXPECT_NEAR(grey.r, grey.g, 1e-5f) << name;
  }
  const vec3 plain = mean_rgb(render_with(scene, "shadow-map"));
  EXPECT_NEAR(plain.r, plain.g, 1e-5f);
}

// The shadow TF replaces the TF for the maps only: a transparent shadow TF
// gives exactly the unshadowed image.
TEST(ShadowMapRelations, SeparateShadowTransferFunctionDrivesTheMaps) {
  Scene scene = floor_scene("spheres", testing::step_tf(0.3f, vec3(0.8f, 0.5f, 0.3f), 0.3f), point_light());
  scene.set_shadow_transfer_function(testing::step_tf(0.0f, vec3(1.0f), 0.0f));
  const Image unshadowed = render_with(scene, "shadow-rays", {{"shadow_density_scale", 0.0}});
  for (const char* name : kShadowMaps) {
    EXPECT_LT(max_abs_error(render_with(scene, name), unshadowed), 1e-6) << name;
  }
}

// With no ambient light an image is linear in the lights: two lights render
// as the sum of each alone (exactly for the deterministic maps; the CSSM's
// noise depends on the light's index, so its sum agrees within noise).
TEST(ShadowMapRelations, EveryLightHasItsOwnMap) {
  const Light a = slanted_directional();
  const Light b = point_light();
  Scene both = floor_scene("spheres", testing::step_tf(0.3f, vec3(0.8f, 0.5f, 0.3f), 0.3f), a);
  both.set_lights({a, b});
  Scene only_a = both, only_b = both;
  only_a.set_lights({a});
  only_b.set_lights({b});
  for (const char* name : kShadowMaps) {
    const Image sum_ab = render_with(both, name);
    const Image image_a = render_with(only_a, name);
    const Image image_b = render_with(only_b, name);
    Image sum = image_a;
    for (std::size_t i = 0; i < sum.pixel_count(); ++i) sum.data()[i] += image_b.data()[i];
    std::printf("[shadow maps] two lights, %s: rmse to the sum of single-light images %.3g\n", name, rmse(sum_ab, sum));
    EXPECT_LT(rmse(sum_ab, sum), std::string(name) == "cssm" ? 0.02 : 1e-5) << name;
  }
}

// A point light inside the volume uses a cube map; the grey deep shadow map
// with many nodes still matches shadow-rays.
TEST(ShadowMapRelations, PointLightInsideTheVolumeUsesACubeMap) {
  Scene scene = procedural_scene("spheres", ivec3(32), 40);
  scene.set_transfer_function(testing::step_tf(0.3f, vec3(0.8f, 0.6f, 0.4f), 0.25f));
  Light light;
  light.type = LightType::Point;
  light.position = vec3(0.0f, -4.0f, 2.0f);
  light.intensity = 150.0f;
  scene.set_lights({light});
  const Image reference = render_with(scene, "shadow-rays");
  const Image deep = render_with(scene, "deep-shadow-map",
                                 {{"nodes", 16.0}, {"tolerance", 0.002}, {"colored", false}, {"filter", "bilinear"}});
  std::printf("[shadow maps] cube map, grey deep shadow map vs shadow-rays: rmse %.4g\n", rmse(deep, reference));
  EXPECT_LT(rmse(deep, reference), 0.01);
  const TechniqueInfo& info = find_technique("deep-shadow-map");
  auto t = info.create();
  ParameterValues params(info.parameters);
  params.set("resolution", 256.0);
  t->prepare(scene, params);
  EXPECT_EQ(t->aux_bytes(), 6u * 128u * 128u * 3u * 4u * sizeof(float));  // faces of half the resolution
}

struct RebuildCase {
  const char* name;
  int values_per_texel;
  const char* query_param;  // changes the lookups only
  ParameterValue query_value;
  const char* map_param;  // changes the maps
  ParameterValue map_value;
};

// Maps are rebuilt when the data, TF, shadow TF, lights, clip planes, step
// or map parameters change, and only then; their memory is resolution^2 *
// values per texel * 4 bytes per light.
TEST(ShadowMapRelations, RebuildOnlyWhatChangedAndReportMemory) {
  const RebuildCase cases[] = {
      {"shadow-map", 1, "pcf_radius", 2.0, "threshold", 0.3},
      {"deep-shadow-map", 12, "filter", std::string("bilinear"), "nodes", 4.0},
      {"cssm", 3, "offsets", std::string("21"), "seed", 3.0},
  };
  for (const RebuildCase& c : cases) {
    SCOPED_TRACE(c.name);
    Scene scene = floor_scene("spheres", testing::step_tf(0.3f, vec3(0.8f), 0.3f), slanted_directional());
    const TechniqueInfo& info = find_technique(c.name);
    ParameterValues params(info.parameters);
    params.set("resolution", 256.0);
    auto t = info.create();
    std::uint64_t expected = 0;
    auto prepare_expecting = [&](const char* what, bool rebuild) {
      t->prepare(scene, params);
      expected += rebuild;
      EXPECT_EQ(t->rebuilds(), expected) << what;
    };
    prepare_expecting("first prepare", true);
    EXPECT_EQ(t->aux_bytes(), 256u * 256u * unsigned(c.values_per_texel) * sizeof(float));
    prepare_expecting("nothing changed", false);
    Camera camera = scene.camera();
    camera.orbit(10.0f, 0.0f);
    scene.set_camera(camera);
    prepare_expecting("camera move", false);
    scene.set_material(Material{});
    prepare_expecting("material", false);
    params.set(c.query_param, c.query_value);
    prepare_expecting("query parameter", false);
    scene.set_lights({slanted_directional(), point_light()});
    prepare_expecting("lights", true);
    EXPECT_EQ(t->aux_bytes(), 2u * 256u * 256u * unsigned(c.values_per_texel) * sizeof(float));
    scene.set_transfer_function(testing::step_tf(0.3f, vec3(0.8f), 0.4f));
    prepare_expecting("TF", true);
    scene.set_shadow_transfer_function(testing::step_tf(0.3f, vec3(0.8f), 0.2f));
    prepare_expecting("shadow TF", true);
    scene.set_clip_planes({vec4(0.0f, 0.0f, 1.0f, 5.0f)});
    prepare_expecting("clip planes", true);
    RenderSettings r = scene.render();
    r.step = 1.0f;
    scene.set_render(r);
    prepare_expecting("step", true);
    r.width = 32;
    scene.set_render(r);
    prepare_expecting("image size", false);
    params.set(c.map_param, c.map_value);
    prepare_expecting("map parameter", true);
    params.set("resolution", 512.0);
    prepare_expecting("resolution", true);
  }
}

// Bad parameters name themselves; maps over the memory budget fail before
// allocating, and a technique whose prepare() failed refuses to render
// instead of reading missing maps.
TEST(ShadowMapRelations, BadParametersAndOversizedMapsFailCleanly) {
  const Scene scene = floor_scene("spheres", testing::step_tf(0.3f, vec3(0.8f), 0.3f), slanted_directional());
  for (const char* name : kShadowMaps) {
    SCOPED_TRACE(name);
    const TechniqueInfo& info = find_technique(name);
    ParameterValues params(info.parameters);
    try {
      params.set("resolution", 100.0);
      ADD_FAILURE() << "resolution 100 accepted";
    } catch (const InvalidArgument& e) {
      EXPECT_EQ(e.name(), "resolution");
    }
    params.set("resolution", 4096.0);
    auto t = info.create();
    const std::uint64_t budget = memory_budget_bytes();
    set_memory_budget_bytes(16u << 20);  // a 4096^2 map of even one float per texel needs 64 MiB
    EXPECT_THROW(t->prepare(scene, params), OutOfMemoryBudget);
    set_memory_budget_bytes(budget);
    Image image;
    EXPECT_THROW(t->render(scene, image), InvalidArgument);
    params.set("resolution", 256.0);
    t->prepare(scene, params);
    t->render(scene, image);
    EXPECT_EQ(image.width(), 48);
  }
}

}  // namespace
}  // namespace penumbra

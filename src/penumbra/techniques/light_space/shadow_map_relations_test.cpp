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
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>

namespace penumbra {
namespace {

using testing::procedural_scene;

// Renders with 256^2 maps (unless `params` says otherwise), which resolve
// these 32^3 volumes finely (a texel is about 0.2 voxel) and keep tests fast.
Image render_small_maps(const Scene& scene, const std::string& technique, ParameterSettings params = {}) {
  if (find_technique(technique).parameters.find("resolution")) params.emplace("resolution", 256.0);
  return testing::render_with(scene, technique, params);
}

const char* const kShadowMaps[] = {"shadow-map", "deep-shadow-map", "cssm"};

// An orthographic camera looking straight down at `target`, `height` world
// units of it in view.
Camera top_down_camera(vec3 target, float height) {
  Camera camera;
  camera.eye = vec3(target.x, target.y, 200.0f);
  camera.target = target;
  camera.up = vec3(0.0f, 1.0f, 0.0f);
  camera.projection = Projection::Orthographic;
  camera.ortho_height = height;
  return camera;
}

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
  scene.set_camera(top_down_camera(vec3(16.0f, 0.0f, 0.0f), 110.0f));
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
    const Image reference = render_small_maps(scene, "shadow-rays");
    for (const char* name : kShadowMaps) {
      SCOPED_TRACE(std::string(name) + (light.type == LightType::Point ? " point" : " directional"));
      const Image image = render_small_maps(scene, name);
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
  const Image unshadowed = render_small_maps(scene, "shadow-rays", {{"shadow_density_scale", 0.0}});
  for (const char* name : kShadowMaps) {
    SCOPED_TRACE(name);
    const Image image = render_small_maps(scene, name);
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
// green. Under the paper's colour model red passes the red shell almost
// freely (red / green > 2, red > 0.8 of unshadowed); under the chromatic
// model (the default) red still passes more than green (> 1.4x), and the
// geometric mean of r, g, b is the grey transmittance (light_ray.h): per
// pixel of the deep shadow map it matches shadow-rays within 0.03 on
// average, and the CSSM's mean colour is the deep map's within 0.03. The plain shadow
// map and the uncoloured variants stay grey.
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
  const Image reference = render_small_maps(scene, "shadow-rays");
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
  vec3 deep_chromatic(0.0f);
  for (const char* name : {"deep-shadow-map", "cssm"}) {
    const vec3 paper = mean_rgb(render_small_maps(scene, name, {{"color_model", std::string("paper")}}));
    std::printf("[shadow maps] red shell, %s, paper colours: shadow rgb %.3f %.3f %.3f (unshadowed %.3f) over %zu "
                "pixels\n",
                name, paper.r, paper.g, paper.b, lit, shell_shadow.size());
    EXPECT_GT(paper.r, 2.0f * paper.g) << name;
    EXPECT_GT(paper.r, 0.8f * lit) << name << ": red passes the red shell";
    const Image chromatic = render_small_maps(scene, name);
    const vec3 c = mean_rgb(chromatic);
    std::printf("[shadow maps] red shell, %s, chromatic: shadow rgb %.3f %.3f %.3f\n", name, c.r, c.g, c.b);
    EXPECT_GT(c.r, 1.4f * c.g) << name;
    if (std::string(name) == "deep-shadow-map") {
      // Per pixel, not for the noisy CSSM (the cube root of a product of
      // noisy channels is biased low); the CSSM is compared with it instead.
      double geometric_error = 0.0;
      for (int i : shell_shadow) {
        const vec3 p = glm::max(vec3(chromatic.data()[i]), vec3(0.0f));
        geometric_error += std::abs(std::cbrt(p.r * p.g * p.b) - reference.data()[i].r);
      }
      geometric_error /= double(shell_shadow.size());
      std::printf("[shadow maps] red shell, deep-shadow-map, chromatic: |cbrt(rgb) - shadow-rays| %.4f\n",
                  geometric_error);
      EXPECT_LT(geometric_error, 0.03) << "the chromatic model keeps the grey darkening";
      deep_chromatic = c;
    } else {
      EXPECT_LT(max_component(glm::abs(c - deep_chromatic)), 0.03f) << "the CSSM estimates what the deep map holds";
    }
    const vec3 grey = mean_rgb(render_small_maps(scene, name, {{"colored", false}}));
    EXPECT_NEAR(grey.r, grey.g, 1e-5f) << name;
  }
  const vec3 plain = mean_rgb(render_small_maps(scene, "shadow-map"));
  EXPECT_NEAR(plain.r, plain.g, 1e-5f);
}

// Mean luminance (Rec. 709) of the pixels of `mask`.
double mean_luminance(const Image& image, const std::vector<int>& mask) {
  double sum = 0.0;
  for (int i : mask) {
    const vec4 p = image.data()[i];
    sum += 0.2126 * p.r + 0.7152 * p.g + 0.0722 * p.b;
  }
  return sum / double(mask.size());
}

// The head CT (scenes/head-directional.json, bone rendered near white) over
// its floor: the darkening the skull's shadow brings to the floor (mean
// luminance of the visible floor pixels, unshadowed minus shadowed) under
// the coloured deep shadow map and CSSM, with their default chromatic
// colours, is within 10 % of shadow-rays'. The paper's colour model lets
// the near-white bone transmit: less than half the darkening is left.
TEST(ShadowMapRelations, HeadCtFloorShadowDarkensAsUnderShadowRays) {
  if (!std::filesystem::exists(std::filesystem::path(PENUMBRA_SHARED_DATA_DIR) /
                               "ct_head_cranium_256x256x108_int16.nhdr")) {
    GTEST_SKIP() << "no head CT in " << PENUMBRA_SHARED_DATA_DIR;
  }
  const int size = 32;
  Scene scene = testing::repository_scene("scenes/head-directional.json", size);
  Camera camera = scene.camera();  // from above and behind, so that the floor shadow is in view
  camera.eye = vec3(0.0f, -250.0f, 500.0f);
  camera.target = vec3(0.0f, -60.0f, -85.0f);
  camera.up = vec3(0.0f, 1.0f, 0.0f);
  camera.fov_deg = 40.0f;
  scene.set_camera(camera);
  RenderSettings render = scene.render();
  render.ert_threshold = 0.99f;  // the scene turns early termination off; the test does not need that
  scene.set_render(render);
  const CameraView view = scene.camera().view();
  const Box3 box = scene.volume().world_box();
  const Plane floor = scene.planes().at(0);
  std::vector<int> floor_pixels;
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const Ray ray = view.pixel_ray(float(x) + 0.5f, float(y) + 0.5f, size, size);
      if (!intersect_box(ray, box, 0.0f, kInfinity).empty()) continue;
      const float facing = glm::dot(ray.direction, floor.normal);
      if (facing < 0.0f && glm::dot(floor.point - ray.origin, floor.normal) / facing > 0.0f) {
        floor_pixels.push_back(y * size + x);
      }
    }
  }
  ASSERT_GT(floor_pixels.size(), 200u);
  const double unshadowed = mean_luminance(render_small_maps(scene, "shadow-rays", {{"shadow_density_scale", 0.0}}),
                                           floor_pixels);
  const double reference = unshadowed - mean_luminance(render_small_maps(scene, "shadow-rays"), floor_pixels);
  ASSERT_GT(reference, 0.02) << "the skull should shadow the floor";
  for (const char* name : {"deep-shadow-map", "cssm"}) {
    const double darkening = unshadowed - mean_luminance(render_small_maps(scene, name), floor_pixels);
    const double paper =
        unshadowed - mean_luminance(render_small_maps(scene, name, {{"color_model", std::string("paper")}}), floor_pixels);
    std::printf("[shadow maps] head CT floor, %s: darkening %.4f (chromatic), %.4f (paper) vs shadow-rays %.4f: "
                "%.3f, %.3f of it\n",
                name, darkening, paper, reference, darkening / reference, paper / reference);
    EXPECT_NEAR(darkening / reference, 1.0, 0.1) << name;
    EXPECT_LT(paper / reference, 0.5) << name << ": the scene should show what the paper's colours lose";
  }
}

// A homogeneous medium cut by a clip plane (z <= 6), the light 10 degrees
// above the cut face, seen from above: the face is dim (its samples' light
// rays run a long way through the medium), and uniform under shadow-rays.
Scene grazing_face_scene() {
  Scene scene = procedural_scene("slab", ivec3(32), 48);
  scene.set_transfer_function(testing::step_tf(0.5f, vec3(0.9f), 0.7f));
  scene.set_clip_planes({vec4(0.0f, 0.0f, -1.0f, 6.0f)});
  Light light;
  light.direction = glm::normalize(vec3(1.0f, 0.35f, -0.19f));  // about 10 degrees above the face
  scene.set_lights({light});
  Material m;
  m.ambient = 0.0f;
  scene.set_material(m);
  scene.set_camera(top_down_camera(vec3(0.0f, 0.0f, 6.0f), 20.0f));
  return scene;
}

// Coefficient of variation (std / mean) of the luminance over the image:
// stripes on the uniform face.
double luminance_variation(const Image& image) {
  double sum = 0.0, sum_sq = 0.0;
  for (const vec4& p : image.pixels()) {
    const double y = 0.2126 * p.r + 0.7152 * p.g + 0.0722 * p.b;
    sum += y;
    sum_sq += y * y;
  }
  const double n = double(image.pixel_count()), mean = sum / n;
  return std::sqrt(std::max(0.0, sum_sq / n - mean * mean)) / mean;
}

// CSSM: with the paper's filter the offsets read rays that have not entered
// the medium at the sample's depth, and the face comes out 3x too bright;
// the depth-aware filter is within 15 % of shadow-rays' mean luminance.
TEST(ShadowMapRelations, CssmDoesNotLeakOnAGrazingCutFace) {
  const Scene scene = grazing_face_scene();
  std::vector<int> all(48 * 48);
  for (int i = 0; i < 48 * 48; ++i) all[i] = i;
  const Image reference_image = render_small_maps(scene, "shadow-rays");
  testing::save_test_image(reference_image, "grazing-shadow-rays.png");
  const double reference = mean_luminance(reference_image, all);
  const Image fixed_image = render_small_maps(scene, "cssm");
  testing::save_test_image(fixed_image, "grazing-cssm.png");
  const double fixed = mean_luminance(fixed_image, all) / reference;
  const double paper = mean_luminance(render_small_maps(scene, "cssm", {{"filter", std::string("paper")}}), all) / reference;
  std::printf("[shadow maps] grazing cut face: shadow-rays %.4f; cssm %.3fx of it (paper filter %.3fx)\n", reference,
              fixed, paper);
  EXPECT_NEAR(fixed, 1.0, 0.15);
  EXPECT_GT(paper, 2.0) << "the scene should show the paper filter's leak";
}

// Shadow map and deep shadow map: without the slope-scaled bias the
// nearest texel's ray enters the face before or after the sample's, and the
// uniform face shows stripes (the luminance varies over the image); with it
// the variation is a fraction of that. The deep shadow map, with nodes
// enough to follow the ray, also matches shadow-rays' mean within 10 %.
// (The shadow map lights everything in front of its 0.5-opacity depth: the
// face is several times brighter than shadow-rays by its model.)
TEST(ShadowMapRelations, SlopeScaledBiasRemovesAcneOnAGrazingCutFace) {
  const Scene scene = grazing_face_scene();
  std::vector<int> all(48 * 48);
  for (int i = 0; i < 48 * 48; ++i) all[i] = i;
  const double reference = mean_luminance(render_small_maps(scene, "shadow-rays"), all);
  const std::pair<const char*, ParameterSettings> cases[] = {
      {"deep-shadow-map", {{"nodes", 16.0}, {"tolerance", 0.002}}}, {"shadow-map", {}}};
  for (const auto& [name, params] : cases) {
    ParameterSettings without = params;
    without["slope_bias"] = 0.0;
    const Image fixed_image = render_small_maps(scene, name, params);
    testing::save_test_image(fixed_image, std::string("grazing-") + name + ".png");
    testing::save_test_image(render_small_maps(scene, name, without), std::string("grazing-") + name + "-no-slope-bias.png");
    const double fixed = luminance_variation(fixed_image);
    const double old = luminance_variation(render_small_maps(scene, name, without));
    const double mean = mean_luminance(fixed_image, all) / reference;
    std::printf("[shadow maps] grazing cut face, %s: luminance variation %.4f (%.4f without slope bias); mean %.3fx "
                "shadow-rays'\n",
                name, fixed, old, mean);
    EXPECT_LT(fixed, 0.3 * old) << name;
    if (std::string(name) == "deep-shadow-map") {
      EXPECT_NEAR(mean, 1.0, 0.1);
    }
  }
}

// The CSSM's offsets are in texels of its map, so a finer map blurs less:
// the soft band the paper's filter puts along the hard shadow edge of an
// opaque half-plane (pixels more than 0.05 off shadow-rays) narrows with the
// resolution (offsets scaled 4x to make the band a few pixels wide at
// 256^2). With the offsets in texels of a 1024^2 map, as before issue 16,
// the band kept its width: the offsets grew with the map.
TEST(ShadowMapRelations, CssmImprovesWithResolution) {
  const Scene scene = floor_scene("edge", testing::step_tf(0.5f, vec3(0.0f), 1.0f), slanted_directional());
  const Image reference = render_small_maps(scene, "shadow-rays");
  double previous = kInfinity;
  for (double resolution : {256.0, 1024.0}) {
    const double band = fraction_differing(
        render_small_maps(scene, "cssm", {{"resolution", resolution}, {"filter", std::string("paper")}, {"offset_scale", 4.0}}),
        reference, 0.05f);
    std::printf("[shadow maps] cssm edge at %.0f^2, offsets x4: %.4f of pixels off shadow-rays\n", resolution, band);
    EXPECT_LT(band, 0.5 * previous) << resolution;
    previous = band;
  }
}

// The shadow TF replaces the TF for the maps only: a transparent shadow TF
// gives exactly the unshadowed image.
TEST(ShadowMapRelations, SeparateShadowTransferFunctionDrivesTheMaps) {
  Scene scene = floor_scene("spheres", testing::step_tf(0.3f, vec3(0.8f, 0.5f, 0.3f), 0.3f), point_light());
  scene.set_shadow_transfer_function(testing::step_tf(0.0f, vec3(1.0f), 0.0f));
  const Image unshadowed = render_small_maps(scene, "shadow-rays", {{"shadow_density_scale", 0.0}});
  for (const char* name : kShadowMaps) {
    EXPECT_LT(max_abs_error(render_small_maps(scene, name), unshadowed), 1e-6) << name;
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
    const Image sum_ab = render_small_maps(both, name);
    const Image image_a = render_small_maps(only_a, name);
    const Image image_b = render_small_maps(only_b, name);
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
  const Image reference = render_small_maps(scene, "shadow-rays");
  const Image deep = render_small_maps(scene, "deep-shadow-map",
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
      {"cssm", 4, "offsets", std::string("21"), "seed", 3.0},
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

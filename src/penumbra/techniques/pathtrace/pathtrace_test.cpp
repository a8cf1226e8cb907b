// pathtrace against shadow-rays (single scattering), the white furnace and
// the analytic single-scattering solution of a homogeneous slab; plus its
// progressive machinery (seeds, stopping at a target error, parameters).
#include "penumbra/analysis/image_metrics.h"
#include "penumbra/base/error.h"
#include "penumbra/base/parallel.h"
#include "penumbra/techniques/pathtrace/pathtrace.h"
#include "penumbra/techniques/registry.h"
#include "test_scene.h"

#include <gtest/gtest.h>

#include <cmath>

namespace penumbra {
namespace {

using testing::procedural_scene;
using testing::render_with;
using testing::step_tf;

struct Rendered {
  Image image;
  Image standard_error;
  RenderStats stats;
};

Rendered pathtrace(const Scene& scene, const ParameterSettings& settings) {
  const TechniqueInfo& info = find_technique("pathtrace");
  ParameterValues params(info.parameters);
  params.apply(settings, true);
  auto t = info.create();
  t->prepare(scene, params);
  Rendered r;
  t->render(scene, r.image, &r.stats);
  r.standard_error = pathtrace_estimate(*t)->standard_error;
  return r;
}

// sqrt of the mean squared standard error: the RMSE that noise alone gives.
double noise_rmse(const Image& standard_error) {
  double sum = 0.0;
  for (const vec4& p : standard_error.pixels()) sum += double(p.r) * p.r + double(p.g) * p.g + double(p.b) * p.b;
  return std::sqrt(sum / (3.0 * double(standard_error.pixel_count())));
}

// Coloured spheres over a floor, a directional and a point light, no
// ambient, no early ray termination and a fine step, so shadow-rays is the
// single-scattering integral up to a small discretisation error.
Scene single_scattering_scene() {
  Scene scene = procedural_scene("spheres", ivec3(32), 32);
  TransferFunction tf({{0.0f, vec3(1.0f, 0.6f, 0.3f), 0.0f},
                       {0.3f, vec3(1.0f, 0.6f, 0.3f), 0.15f},
                       {1.0f, vec3(0.5f, 0.8f, 1.0f), 0.6f}});
  tf.set_range(vec2(0.0f, 1.0f));
  scene.set_transfer_function(tf);
  Light sun;
  sun.direction = glm::normalize(vec3(0.5f, 0.7f, -1.0f));
  Light bulb;
  bulb.type = LightType::Point;
  bulb.position = vec3(-30.0f, -20.0f, 25.0f);
  bulb.intensity = 1500.0f;
  bulb.color = vec3(0.6f, 0.7f, 1.0f);
  scene.set_lights({sun, bulb});
  Material m;
  m.ambient = 0.0f;
  m.phase_g = 0.3f;
  scene.set_material(m);
  scene.set_planes({Plane{vec3(0.0f, 0.0f, -18.0f), vec3(0.0f, 0.0f, 1.0f), vec3(0.8f)}});
  Camera camera = scene.camera();
  camera.eye += vec3(0.0f, 0.0f, 30.0f);
  scene.set_camera(camera);
  RenderSettings r = scene.render();
  r.step = 0.25f;
  r.ert_threshold = 1.0f;
  scene.set_render(r);
  return scene;
}

// Each spp renders independently; with per-sample seeds the first n paths of
// every pixel are the same in each run, as progressive rendering would have
// them.
TEST(PathTrace, SingleScatteringConvergesToShadowRays) {
  const Scene scene = single_scattering_scene();
  const Image reference = render_with(scene, "shadow-rays");
  std::vector<double> errors;
  Rendered last;
  for (const int spp : {4, 16, 64, 256}) {
    last = pathtrace(scene, {{"mode", std::string("single")}, {"spp", double(spp)}, {"min_spp", 4.0}});
    errors.push_back(rmse(last.image, reference));
  }
  // RMSE^2 = noise^2 + bias^2 with noise ~ 1/sqrt(spp): each 4x more paths
  // should halve it. Between 16 and 256 paths: a factor 4 for pure noise;
  // allow 2.8 .. 5.7 (slope 0.37 .. 0.63 in log-log).
  const double ratio = errors[1] / errors[3];
  EXPECT_GT(ratio, 2.8) << errors[0] << " " << errors[1] << " " << errors[2] << " " << errors[3];
  EXPECT_LT(ratio, 5.7);
  EXPECT_GT(errors[0], errors[1]);
  EXPECT_GT(errors[2], errors[3]);
  // At 256 paths the error is what the per-pixel variance estimate predicts
  // for noise alone (within 25%: the estimate is itself noisy and some
  // pixels have heavy tails), plus 0.0025 for the discretisation of the
  // quarter-voxel midpoint rule against the continuous integral. Observed:
  // RMSE 0.027, 0.013, 0.0064, 0.0033 at 4, 16, 64, 256 paths; noise alone
  // 0.0031, so the bias is ~0.0012.
  const double noise = noise_rmse(last.standard_error);
  EXPECT_LT(errors[3], 1.25 * noise + 0.0025) << "noise " << noise;
  EXPECT_LT(errors[3], 0.02);
  // The image is lit, not black: the error is small relative to it.
  EXPECT_GT(luminance(testing::mean_rgb(reference, 0, 0, 32, 32)), 0.1f);
}

// Albedo 1 (white TF, material albedo 1), a uniform environment of radiance
// 1 and nothing else: every path carries radiance 1 whatever it does, so
// every pixel converges to exactly 1 (Fredholm: L = L_env is the solution).
TEST(PathTrace, WhiteFurnaceImageEqualsTheEnvironment) {
  Scene scene = procedural_scene("slab", ivec3(24), 24);
  // Optical depth ~2.3 across the box, so paths scatter many times.
  scene.set_transfer_function(step_tf(0.5f, vec3(1.0f), 0.1f));
  Light env;
  env.type = LightType::Environment;
  scene.set_lights({env});
  Material m;
  m.albedo = 1.0f;
  m.phase_g = 0.4f;
  m.ambient = 0.0f;
  scene.set_material(m);
  scene.set_background(vec3(0.0f));
  const Rendered furnace =
      pathtrace(scene, {{"mode", std::string("multiple")}, {"spp", 128.0}, {"max_bounces", 100000.0}});
  double sum = 0.0, variance = 0.0, z2 = 0.0;
  int medium_pixels = 0, outliers = 0;
  for (std::size_t i = 0; i < furnace.image.pixel_count(); ++i) {
    const vec4 p = furnace.image.pixels()[i];
    const vec4 se = furnace.standard_error.pixels()[i];
    ASSERT_NEAR(p.g, p.r, 1e-6f);
    if (p.a == 0.0f) {
      ASSERT_EQ(p.r, 1.0f);  // the environment seen directly
      continue;
    }
    ++medium_pixels;
    sum += p.r;
    variance += double(se.r) * se.r;
    const double z = (double(p.r) - 1.0) / std::max(double(se.r), 1e-6);
    z2 += z * z;
    outliers += std::abs(z) > 4.0;
  }
  ASSERT_GT(medium_pixels, 200);
  // The image mean over the medium within 4 standard errors of 1.
  EXPECT_NEAR(sum / medium_pixels, 1.0, 4.0 * std::sqrt(variance) / medium_pixels);
  // Per pixel, the deviations match the variance estimates: mean z^2 near 1
  // (its sd is ~0.1 for 300 normal pixels; path sums are skewed, so allow
  // 0.6 .. 1.6) and few 4-sigma outliers (heavy tails at 128 paths).
  EXPECT_GT(z2 / medium_pixels, 0.6);
  EXPECT_LT(z2 / medium_pixels, 1.6);
  EXPECT_LE(outliers, 3);
  // Not vacuous: single scattering loses what scatters more than once.
  const Rendered single = pathtrace(scene, {{"spp", 8.0}, {"mode", std::string("single")}});
  EXPECT_LT(testing::mean_rgb(single.image, 8, 8, 16, 16).r, 0.9f);
}

// A homogeneous slab of thickness D and extinction sigma (tau = sigma D),
// albedo a, lit straight down by a directional light of intensity I, seen
// straight down (reflection) and straight up (transmission) by orthographic
// cameras. Single scattering (the integral over depth z of the source
// a sigma p I e^(-sigma z) attenuated toward the viewer):
//   reflected   a p(cos = -1) I (1 - e^(-2 tau)) / 2
//   transmitted a p(cos = +1) I tau e^(-tau)
// with p = phase_hg_4pi. Finite lateral extent does not matter: both light
// and view paths are vertical, inside the box.
TEST(PathTrace, HomogeneousSlabMatchesAnalyticSingleScattering) {
  const int size = 32;
  const float depth = float(size - 1);
  const float tau = 1.2f;
  Scene scene = procedural_scene("slab", ivec3(size), 16);
  scene.set_transfer_function(step_tf(0.5f, vec3(1.0f), 1.0f - std::exp(-tau / depth)));
  Light sun;
  sun.direction = vec3(0.0f, 0.0f, -1.0f);
  sun.intensity = 1.5f;
  scene.set_lights({sun});
  const float albedo = 0.8f;
  for (const float g : {0.0f, 0.6f}) {
    SCOPED_TRACE(g);
    Material m;
    m.albedo = albedo;
    m.phase_g = g;
    m.ambient = 0.0f;
    scene.set_material(m);
    for (const bool reflected : {true, false}) {
      Camera camera;
      camera.eye = vec3(0.0f, 0.0f, reflected ? 100.0f : -100.0f);
      camera.target = vec3(0.0f);
      camera.up = vec3(0.0f, 1.0f, 0.0f);
      camera.projection = Projection::Orthographic;
      camera.ortho_height = 20.0f;  // inside the 31-unit footprint
      scene.set_camera(camera);
      const Rendered r = pathtrace(scene, {{"mode", std::string("single")}, {"spp", 64.0}});
      const double expected = reflected
                                  ? albedo * phase_hg_4pi(g, -1.0f) * sun.intensity * (1.0 - std::exp(-2.0 * tau)) / 2.0
                                  : albedo * phase_hg_4pi(g, 1.0f) * sun.intensity * tau * std::exp(-tau);
      const double mean = testing::mean_rgb(r.image, 0, 0, 16, 16).r;
      double variance = 0.0;
      for (const vec4& se : r.standard_error.pixels()) variance += double(se.r) * se.r;
      const double standard_error = std::sqrt(variance) / 256.0;
      EXPECT_NEAR(mean, expected, 4.0 * standard_error + 1e-3 * expected) << (reflected ? "reflected" : "transmitted");
    }
  }
}

TEST(PathTrace, MultipleScatteringAddsLightAndZeroAlbedoScattersNothing) {
  Scene scene = single_scattering_scene();
  const Rendered single = pathtrace(scene, {{"mode", std::string("single")}, {"spp", 16.0}});
  const Rendered multiple = pathtrace(scene, {{"mode", std::string("multiple")}, {"spp", 16.0}});
  const float a = luminance(testing::mean_rgb(single.image, 0, 0, 32, 32));
  const float b = luminance(testing::mean_rgb(multiple.image, 0, 0, 32, 32));
  EXPECT_GT(b, 1.02f * a);
  Material m = scene.material();
  m.albedo = 0.0f;
  scene.set_material(m);
  scene.set_planes({});
  const Rendered black = pathtrace(scene, {{"mode", std::string("multiple")}, {"spp", 4.0}});
  EXPECT_EQ(luminance(testing::mean_rgb(black.image, 0, 0, 32, 32)), 0.0f);
}

TEST(PathTrace, SameSeedGivesTheSameImageOnAnyThreadCount) {
  const Scene scene = single_scattering_scene();
  const ParameterSettings settings{{"spp", 8.0}, {"antialias", true}};
  const Rendered a = pathtrace(scene, settings);
  set_thread_count(1);
  const Rendered b = pathtrace(scene, settings);
  set_thread_count(0);
  EXPECT_EQ(max_abs_error(a.image, b.image), 0.0);
  ParameterSettings other = settings;
  other["seed"] = 7.0;
  EXPECT_GT(max_abs_error(a.image, pathtrace(scene, other).image), 0.0);
}

TEST(PathTrace, TargetErrorStopsConvergedPixelsEarly) {
  const Scene scene = single_scattering_scene();
  const double target = 2.0;  // CIE L* units
  const TechniqueInfo& info = find_technique("pathtrace");
  ParameterValues params(info.parameters);
  params.apply({{"spp", 512.0}, {"min_spp", 16.0}, {"target_error", target}, {"mode", std::string("single")}}, true);
  auto t = info.create();
  t->prepare(scene, params);
  Image image;
  t->render(scene, image);
  const PathTraceEstimate& e = *pathtrace_estimate(*t);
  EXPECT_LT(e.paths, std::uint64_t(32 * 32 * 512) / 2) << "most pixels should stop early";
  int stopped = 0;
  for (std::size_t i = 0; i < image.pixel_count(); ++i) {
    const vec4 se = e.standard_error.pixels()[i];
    const int paths = int(se.a);
    ASSERT_GE(paths, 16);
    if (paths == 512) continue;
    ++stopped;
    // A stopped pixel's lightness error was below the target. The estimate
    // keeps per-channel errors only; with channel errors that are not
    // negatively correlated (they come from the same paths), the luminance
    // of the channel errors is between the true luminance error and
    // sqrt(3) times it (Cauchy-Schwarz).
    const double y = luminance(vec3(image.pixels()[i]));
    EXPECT_LE(lightness_standard_error(y, luminance(vec3(se))), std::sqrt(3.0) * target) << "pixel " << i;
  }
  EXPECT_GT(stopped, 100);
  EXPECT_GE(e.passes, 2);
}

TEST(PathTrace, LightnessStandardErrorFollowsCieLightness) {
  // dL*/dY = 116/3 Y^(-2/3): 38.67 at white, 903.3 (linear part) near black.
  EXPECT_NEAR(lightness_standard_error(1.0, 0.01), 0.3867, 1e-4);
  EXPECT_NEAR(lightness_standard_error(0.18, 0.01), 116.0 / 3.0 * std::pow(0.18, -2.0 / 3.0) * 0.01, 1e-9);
  EXPECT_NEAR(lightness_standard_error(0.001, 0.001), 0.9033, 1e-4);
  EXPECT_NEAR(lightness_standard_error(4.0, 0.01), 0.3867, 1e-4);  // a display clips above white
}

TEST(PathTrace, EmptyMediumCostsNoVolumeSamples) {
  Scene scene = single_scattering_scene();
  scene.set_transfer_function(step_tf(0.5f, vec3(1.0f), 0.0f));
  scene.set_planes({});
  scene.set_background(vec3(0.1f, 0.2f, 0.3f));
  const Rendered r = pathtrace(scene, {{"spp", 4.0}});
  EXPECT_EQ(r.stats.samples, 0u);
  EXPECT_EQ(r.stats.rays, 32u * 32u * 4u);
  EXPECT_LT(max_abs_error(r.image, Image(32, 32, vec4(0.1f, 0.2f, 0.3f, 0.0f))), 1e-7);
}

// Area lights shrink to their point and directional limits; distant lights
// keep the directional light's power at any angle.
TEST(PathTrace, AreaLightsApproachTheirPointAndDirectionalLimits) {
  Scene scene = single_scattering_scene();
  const ParameterSettings settings{{"mode", std::string("single")}, {"spp", 16.0}};
  Light bulb = scene.lights()[1];
  scene.set_lights({bulb});
  const Rendered point = pathtrace(scene, settings);
  Light sphere = bulb;
  sphere.type = LightType::Sphere;
  sphere.radius = 0.01f;
  scene.set_lights({sphere});
  // Same random numbers, directions that differ by < 1e-3 rad: nearly equal.
  EXPECT_LT(rmse(pathtrace(scene, settings).image, point.image), 2e-3);
  Light sun = single_scattering_scene().lights()[0];
  scene.set_lights({sun});
  const Rendered directional = pathtrace(scene, settings);
  for (const LightProfile profile : {LightProfile::Uniform, LightProfile::Gaussian}) {
    Light distant = sun;
    distant.type = LightType::Distant;
    distant.profile = profile;
    distant.angle_deg = 0.05f;
    scene.set_lights({distant});
    EXPECT_LT(rmse(pathtrace(scene, settings).image, directional.image), 2e-3);
    // A wider light softens the floor shadow but keeps the light's power:
    // mean luminance within 3% (the cosine at the floor and the phase
    // function average over the spread, which costs O(angle^2) ~ 1%).
    distant.angle_deg = 5.0f;
    scene.set_lights({distant});
    const float wide = luminance(testing::mean_rgb(pathtrace(scene, settings).image, 0, 0, 32, 32));
    EXPECT_NEAR(wide, luminance(testing::mean_rgb(directional.image, 0, 0, 32, 32)), 0.03f * wide);
  }
}

TEST(PathTrace, BadParametersNameTheParameter) {
  const TechniqueInfo& info = find_technique("pathtrace");
  ParameterValues params(info.parameters);
  for (const auto& [name, value] : {std::pair<const char*, ParameterValue>{"spp", 0.0},
                                    {"mode", std::string("double")},
                                    {"max_bounces", -1.0},
                                    {"target_error", -0.5}}) {
    try {
      params.set(name, value);
      ADD_FAILURE() << name << " accepted a bad value";
    } catch (const InvalidArgument& e) {
      EXPECT_EQ(e.name(), name);
    }
  }
}

TEST(PathTrace, AuxBytesAreTheAccumulators) {
  Scene scene = single_scattering_scene();
  const TechniqueInfo& info = find_technique("pathtrace");
  const ParameterValues params(info.parameters);
  auto t = info.create();
  t->prepare(scene, params);
  EXPECT_EQ(pathtrace_estimate(*t), nullptr);
  scene.set_lights(scene.lights());
  t->prepare(scene, params);
  EXPECT_EQ(t->aux_bytes(), 0u);
  RenderSettings r = scene.render();
  r.width = 8;
  r.height = 4;
  scene.set_render(r);
  ParameterValues few = params;
  few.set("spp", 2.0);
  t->prepare(scene, few);
  Image image;
  t->render(scene, image);
  EXPECT_GT(t->aux_bytes(), 32u * 16u);
  EXPECT_EQ(pathtrace_estimate(*t)->paths, 64u);
  EXPECT_EQ(pathtrace_estimate(*find_technique("shadow-rays").create()), nullptr);
}

// Delta tracking's cost grows with the majorant: a density that would make a
// path take millions of collisions (or, at 1e30, never advance) is refused
// up front, naming the key, instead of rendering for ever.
TEST(PathTrace, ADensityThatMakesTrackingUnboundedIsRefused) {
  Scene scene = single_scattering_scene();
  const TechniqueInfo& info = find_technique("pathtrace");
  const ParameterValues params(info.parameters);
  for (const float density : {1e6f, 1e30f}) {
    TransferFunction tf = scene.transfer_function();
    tf.set_density_scale(density);
    scene.set_transfer_function(tf);
    auto t = info.create();
    try {
      t->prepare(scene, params);
      ADD_FAILURE() << "density_scale " << density << " accepted";
    } catch (const InvalidScene& e) {
      EXPECT_EQ(e.key(), "transfer_function.density_scale");
      EXPECT_NE(std::string(e.what()).find("use a density_scale of at most"), std::string::npos) << e.what();
    }
  }
  // The same for the shadow TF, which shadow rays track.
  TransferFunction tf = scene.transfer_function();
  tf.set_density_scale(1.0f);
  scene.set_transfer_function(tf);
  TransferFunction dense = tf;
  dense.set_density_scale(1e30f);
  scene.set_shadow_transfer_function(dense);
  EXPECT_THROW(info.create()->prepare(scene, params), InvalidScene);
  // Dense but bounded media still render.
  scene.set_shadow_transfer_function(std::nullopt);
  tf.set_density_scale(100.0f);
  scene.set_transfer_function(tf);
  EXPECT_NO_THROW(info.create()->prepare(scene, params));
}

}  // namespace
}  // namespace penumbra

namespace penumbra {
namespace {

TEST(PathTrace, ReportsProgressAndStopsWhenAsked) {
  const Scene scene = single_scattering_scene();
  const TechniqueInfo& info = find_technique("pathtrace");
  ParameterValues params(info.parameters);
  params.set("spp", 4.0);
  params.set("min_spp", 2.0);
  auto t = info.create();
  RenderProgress progress;
  t->set_progress(&progress);
  t->prepare(scene, params);
  Image image;
  t->render(scene, image);
  EXPECT_DOUBLE_EQ(progress.fraction(), 1.0);  // every path of the budget taken
  // A stop asked for before (or during) a render ends it with RenderCancelled
  // after the current pass, with the tiles left untouched.
  progress.request_stop();
  RenderStats stats;
  EXPECT_THROW(t->render(scene, image, &stats), RenderCancelled);
  EXPECT_EQ(stats.rays, 0u);
  t->set_progress(nullptr);
  EXPECT_NO_THROW(t->render(scene, image));
}

}  // namespace
}  // namespace penumbra

// Progressive pathtrace (the web viewer's reference): renders of an unchanged
// state add to one estimate; any change starts again.
namespace penumbra {
namespace {

struct ProgressiveRun {
  std::unique_ptr<Technique> technique;
  ParameterValues params;
  Image image;

  ProgressiveRun(const ParameterSettings& settings) : technique(find_technique("pathtrace").create()) {
    params = ParameterValues(find_technique("pathtrace").parameters);
    params.apply(settings, true);
  }
  const PathTraceEstimate& render(const Scene& scene) {
    technique->prepare(scene, params);
    technique->render(scene, image);
    return *pathtrace_estimate(*technique);
  }
};

Scene progressive_test_scene() {
  Scene scene = single_scattering_scene();
  RenderSettings r = scene.render();
  r.width = r.height = 24;
  scene.set_render(r);
  return scene;
}

TEST(PathTraceProgressive, RendersOfTheSameStateAddUpToOneLongerRender) {
  const Scene scene = progressive_test_scene();
  for (const double target_error : {0.0, 2.0}) {
    SCOPED_TRACE(target_error);
    const ParameterSettings base{{"min_spp", 4.0}, {"target_error", target_error}};
    ProgressiveRun one([&] { auto s = base; s["spp"] = 16.0; return s; }());
    const PathTraceEstimate reference = one.render(scene);
    ASSERT_EQ(reference.spp, 16);
    if (target_error > 0.0) {
      ASSERT_LT(reference.paths, std::uint64_t(24 * 24 * 16)) << "some pixels should stop early";
    }
    ProgressiveRun split([&] {
      auto s = base;
      s["spp"] = 8.0;
      s["progressive"] = true;
      return s;
    }());
    EXPECT_EQ(split.render(scene).spp, 8);
    const PathTraceEstimate& e = split.render(scene);
    EXPECT_EQ(e.spp, 16);
    EXPECT_EQ(e.renders, 2);
    EXPECT_EQ(e.paths, reference.paths);
    // The same streams summed in the same order: the same bits.
    EXPECT_EQ(max_abs_error(split.image, one.image), 0.0);
    EXPECT_EQ(max_abs_error(e.standard_error, reference.standard_error), 0.0);
  }
}

TEST(PathTraceProgressive, AnyChangeStartsAgain) {
  Scene scene = progressive_test_scene();
  ProgressiveRun run({{"spp", 4.0}, {"min_spp", 2.0}, {"progressive", true}});
  run.render(scene);
  ASSERT_EQ(run.render(scene).spp, 8);
  const auto fresh = [](const Scene& s, const ParameterValues& params) {
    auto t = find_technique("pathtrace").create();
    t->prepare(s, params);
    Image image;
    t->render(s, image);
    return image;
  };
  Camera camera = scene.camera();
  camera.orbit(10.0f, 0.0f);
  scene.set_camera(camera);
  const PathTraceEstimate& moved = run.render(scene);
  EXPECT_EQ(moved.spp, 4);
  EXPECT_EQ(moved.renders, 1);
  EXPECT_EQ(max_abs_error(run.image, fresh(scene, run.params)), 0.0);
  ASSERT_EQ(run.render(scene).spp, 8);

  std::vector<Light> lights = scene.lights();
  lights[0].type = LightType::Distant;
  lights[0].angle_deg = 4.0f;
  scene.set_lights(lights);
  EXPECT_EQ(run.render(scene).spp, 4);
  EXPECT_EQ(max_abs_error(run.image, fresh(scene, run.params)), 0.0);
  ASSERT_EQ(run.render(scene).spp, 8);

  run.params.set("seed", 3.0);
  EXPECT_EQ(run.render(scene).spp, 4);
  EXPECT_EQ(max_abs_error(run.image, fresh(scene, run.params)), 0.0);
}

// A cancelled render leaves a partial pass in the sums: the next one starts
// again instead of adding to them.
TEST(PathTraceProgressive, ACancelledRenderStartsAgain) {
  const Scene scene = progressive_test_scene();
  ProgressiveRun run({{"spp", 4.0}, {"min_spp", 2.0}, {"progressive", true}});
  ASSERT_EQ(run.render(scene).spp, 4);
  RenderProgress progress;
  progress.request_stop();
  run.technique->set_progress(&progress);
  EXPECT_THROW(run.render(scene), RenderCancelled);
  run.technique->set_progress(nullptr);
  EXPECT_EQ(run.render(scene).spp, 4);
  EXPECT_EQ(run.render(scene).spp, 8);
}

TEST(PathTraceProgressive, StopsAtMaxTotalSppAndIsOffByDefault) {
  const Scene scene = progressive_test_scene();
  ProgressiveRun capped({{"spp", 4.0}, {"min_spp", 2.0}, {"progressive", true}, {"max_total_spp", 6.0}});
  EXPECT_FALSE(capped.render(scene).converged);
  const PathTraceEstimate& full = capped.render(scene);
  EXPECT_EQ(full.spp, 6);
  EXPECT_TRUE(full.converged);
  const Image at_cap = capped.image;
  RenderStats stats;
  capped.technique->prepare(scene, capped.params);
  capped.technique->render(scene, capped.image, &stats);
  EXPECT_EQ(stats.rays, 0u) << "nothing left to add";
  EXPECT_EQ(pathtrace_estimate(*capped.technique)->spp, 6);
  EXPECT_EQ(max_abs_error(capped.image, at_cap), 0.0);

  // Without `progressive` (the CLI), every render is spp paths of its own.
  ProgressiveRun plain({{"spp", 4.0}, {"min_spp", 2.0}});
  plain.render(scene);
  const Image first = plain.image;
  const PathTraceEstimate& again = plain.render(scene);
  EXPECT_EQ(again.spp, 4);
  EXPECT_EQ(again.renders, 1);
  EXPECT_TRUE(again.converged);
  EXPECT_EQ(max_abs_error(plain.image, first), 0.0);
}

}  // namespace
}  // namespace penumbra

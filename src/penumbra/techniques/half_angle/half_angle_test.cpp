// half-angle against shadow-rays (its albedo-0 limit), against ipsvi (Sundén
// et al. 2011, Fig. 8: the two look alike), and the slicing geometry.
//
// Tolerances are mean CIEDE2000 (about one unit = a just-noticeable
// difference). Slices sample the volume where the viewing rays cross them, at
// about the ray caster's step, and the light buffer is bilinear with texels of
// about one voxel; the differences to shadow-rays are resampling at shadow
// edges: a few dE there, well under 1 on average.
#include "penumbra/analysis/image_metrics.h"
#include "penumbra/base/error.h"
#include "penumbra/io/scene_json.h"
#include "penumbra/techniques/half_angle/diffuse_blur.h"
#include "penumbra/techniques/half_angle/slice_geometry.h"
#include "penumbra/techniques/registry.h"
#include "test_scene.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace penumbra {
namespace {

using testing::render_with;
using testing::save_test_image;

Scene floored_spheres(int image_size = 48) { return testing::with_floor(testing::lit_spheres(image_size)); }

// A half-angle instance, and its parameters with light_buffer_size 32.
struct HalfAngleAt32 {
  ParameterValues params{find_technique("half-angle").parameters};
  std::unique_ptr<Technique> technique = find_technique("half-angle").create();
  HalfAngleAt32() { params.set("light_buffer_size", 32.0); }
};

using testing::mean_de;

TEST(HalfAngle, AlbedoZeroMatchesShadowRaysOnTheSpheres) {
  const Scene scene = floored_spheres();
  const Image reference = render_with(scene, "shadow-rays");
  const Image half = render_with(scene, "half-angle");
  save_test_image(reference, "half-angle-spheres-shadow-rays.png");
  save_test_image(half, "half-angle-spheres.png");
  const DeltaEStats de = delta_e_stats(half, reference);
  std::printf("half-angle vs shadow-rays: mean dE %.3f, p99 %.3f\n", de.mean, de.p99);
  EXPECT_LT(de.mean, 0.3);
  EXPECT_LT(de.p99, 3.0);
}

// A light facing the viewer: the slicing axis flips and the eye buffer is
// composited back to front; a point light outside the volume: a perspective
// light buffer.
TEST(HalfAngle, FlippedAxisAndPointLightsMatchShadowRays) {
  Scene scene = floored_spheres();
  Light back;
  back.direction = glm::normalize(vec3(0.3f, -1.0f, -0.4f));
  scene.set_lights({back});
  const double de_back = mean_de(render_with(scene, "half-angle"), render_with(scene, "shadow-rays"));
  Light point;
  point.type = LightType::Point;
  point.position = vec3(30.0f, -50.0f, 60.0f);
  point.intensity = 6000.0f;
  scene.set_lights({point});
  const double de_point = mean_de(render_with(scene, "half-angle"), render_with(scene, "shadow-rays"));
  std::printf("half-angle: backlit mean dE %.3f, point light %.3f\n", de_back, de_point);
  EXPECT_LT(de_back, 0.3);
  EXPECT_LT(de_point, 0.3);
}

// Few slices undersample the volume: the error against shadow-rays falls as
// the slice count rises toward the ray caster's step.
TEST(HalfAngle, MoreSlicesConverge) {
  const Scene scene = floored_spheres();
  const Image reference = render_with(scene, "shadow-rays");
  const double coarse = mean_de(render_with(scene, "half-angle", {{"slices", 24.0}}), reference);
  const double fine = mean_de(render_with(scene, "half-angle", {{"slices", 192.0}}), reference);
  std::printf("half-angle: 24 slices mean dE %.3f, 192 slices %.3f\n", coarse, fine);
  EXPECT_LT(fine, 0.5 * coarse);
}

// Zoomed in, a light buffer of the image's size over the whole box has
// texels several pixels wide; the automatic size then follows ipsvi's texel
// per pixel at the volume and the shadows stay as sharp as shadow-rays'.
TEST(HalfAngle, LightBufferFollowsTheZoom) {
  Scene scene = floored_spheres();
  Camera camera = scene.camera();
  camera.fov_deg /= 4.0f;
  camera.target = scene.volume().world_box().center() + vec3(6.0f, 0.0f, 4.0f);
  scene.set_camera(camera);
  const Image reference = render_with(scene, "shadow-rays");
  const double automatic = mean_de(render_with(scene, "half-angle"), reference);
  const double image_sized = mean_de(render_with(scene, "half-angle", {{"light_buffer_size", 48.0}}), reference);
  std::printf("half-angle zoomed: automatic light buffer mean dE %.3f, image-sized %.3f\n", automatic, image_sized);
  EXPECT_LT(automatic, 0.3);
  EXPECT_LT(automatic, 0.6 * image_sized);
}

// Forward scattering: no cone is no change; a cone lightens shadows as in ipsvi.
TEST(HalfAngle, ForwardScatteringReducesToSingleScatteringWithoutACone) {
  const Scene scene = floored_spheres();
  const Image single = render_with(scene, "half-angle");
  EXPECT_LT(mean_de(render_with(scene, "half-angle", {{"albedo", 0.8}, {"cone_angle_deg", 0.0}}), single), 0.05);
  EXPECT_GT(mean_de(render_with(scene, "half-angle", {{"albedo", 0.8}, {"cone_angle_deg", 30.0}}), single), 0.05);
}

// The light rays are built in prepare(), once per light, data or buffer size
// change; a camera move or a TF change reuses them. A bad light_buffer_size
// fails in prepare(), naming the parameter.
TEST(HalfAngle, BuildsLightRaysOncePerLightAndChecksTheBufferSizeInPrepare) {
  Scene scene = floored_spheres(24);
  HalfAngleAt32 half_angle;
  ParameterValues& params = half_angle.params;
  auto& t = half_angle.technique;
  t->prepare(scene, params);
  EXPECT_EQ(t->rebuilds(), 1u);
  EXPECT_GE(t->aux_bytes(), 32u * 32u * sizeof(Ray)) << "the kept rays are counted";
  Camera camera = scene.camera();
  camera.orbit(25.0f, 10.0f);
  scene.set_camera(camera);
  scene.set_transfer_function(testing::step_tf(0.3f, vec3(1.0f), 0.4f));
  t->prepare(scene, params);
  Image image;
  t->render(scene, image);
  t->prepare(scene, params);
  EXPECT_EQ(t->rebuilds(), 1u) << "camera and TF need no new light rays";
  scene.set_lights(scene.lights());
  t->prepare(scene, params);
  EXPECT_EQ(t->rebuilds(), 2u);
  params.set("light_buffer_size", 48.0);
  t->prepare(scene, params);
  EXPECT_EQ(t->rebuilds(), 3u);
  params.set("light_buffer_size", 8.0);  // in the table's range, not prepare's
  try {
    t->prepare(scene, params);
    ADD_FAILURE() << "light_buffer_size 8 accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.name(), "light_buffer_size");
  }
}

// aux_bytes counts what the per-pixel buffers hold: after a smaller image
// they keep their capacity, and the count says so.
TEST(HalfAngle, AuxBytesCountWhatTheBuffersHoldAfterTheImageShrinks) {
  Scene scene = floored_spheres(24);
  HalfAngleAt32 half_angle;
  auto render_at = [&](int side) {
    RenderSettings r = scene.render();
    r.width = r.height = side;
    scene.set_render(r);
    half_angle.technique->prepare(scene, half_angle.params);
    Image image;
    half_angle.technique->render(scene, image);
    return half_angle.technique->aux_bytes();
  };
  const std::uint64_t large = render_at(64);
  const std::uint64_t small = render_at(16);
  EXPECT_GE(large, 64u * 64u * sizeof(vec4));  // at least the colour sums
  // The light buffer's size is fixed here, so nothing was freed or grown.
  EXPECT_EQ(small, large) << "the buffers still hold a 64x64 image";
}

// The diffuse blur after each slice covers every texel the light has
// reached, which is the same as blurring the whole buffer: a dark patch at
// the buffer's edge, attenuated by the first slice, keeps spreading while the
// second slice lies across the buffer from it. Against a brute-force blur of
// the whole buffer, pass for pass. (Blurring only the slice's rectangle, as
// half-angle did before issue 21, leaves the patch as the first slice left
// it: max difference 0.27.)
TEST(HalfAngle, DiffuseBlurCoversTheWholeBuffer) {
  const int n = 16;
  std::vector<vec4> buffer(std::size_t(n * n), vec4(1.0f));
  for (int y = 6; y < 10; ++y) buffer[std::size_t(n * y)] = vec4(1.0f, 0.2f, 0.3f, 0.4f);  // column 0
  std::vector<vec4> expected = buffer;
  auto blur_all = [&](vec2 variance) {  // the same binomial passes over every texel
    for (int axis = 0; axis < 2; ++axis) {
      const int passes = int(std::ceil(variance[axis] / 0.5f));
      const float w = variance[axis] / (2.0f * float(passes));
      for (int pass = 0; pass < passes; ++pass) {
        std::vector<vec4> out = expected;
        for (int y = 0; y < n; ++y) {
          for (int x = 0; x < n; ++x) {
            const ivec2 step = axis == 0 ? ivec2(1, 0) : ivec2(0, 1);
            const ivec2 a = glm::clamp(ivec2(x, y) - step, ivec2(0), ivec2(n - 1));
            const ivec2 b = glm::clamp(ivec2(x, y) + step, ivec2(0), ivec2(n - 1));
            const vec4 c = expected[std::size_t(x + n * y)];
            const vec4 sum = (1.0f - 2.0f * w) * c + w * (expected[std::size_t(a.x + n * a.y)] +
                                                          expected[std::size_t(b.x + n * b.y)]);
            out[std::size_t(x + n * y)] = vec4(c.x, sum.y, sum.z, sum.w);
          }
        }
        expected = out;
      }
    }
  };
  std::vector<vec4> scratch(buffer.size(), vec4(1.0f));  // the unlit constant outside `lit`, as the renderer keeps it
  TexelRect lit{n, n, 0, 0};
  const vec2 variance(0.8f, 0.6f);
  blur_after_slice(buffer, scratch, n, TexelRect{0, 4, 4, 12}, lit, variance);  // over the patch
  blur_all(variance);
  for (int k = 0; k < 3; ++k) {
    blur_after_slice(buffer, scratch, n, TexelRect{10, 0, 16, 16}, lit, variance);  // across the buffer
    blur_all(variance);
  }
  float error = 0.0f;
  for (std::size_t i = 0; i < buffer.size(); ++i) {
    error = std::max(error, max_component(glm::abs(buffer[i] - expected[i])));
  }
  std::printf("diffuse blur against the whole buffer's: max difference %.3g\n", error);
  EXPECT_LT(error, 1e-6f);
  EXPECT_GT(1.0f - expected[std::size_t(3 + n * 5)].y, 0.01f) << "the test needs the patch to have spread";
}

// Fig. 8 of Sundén et al.: ipsvi and half-angle slicing look alike. Same
// optical model here, so they agree as closely as each agrees with
// shadow-rays: on the spheres with forward scattering, and on the engine CT
// with and without it.
TEST(HalfAngleVersusIpsvi, AgreeOnTheSpheresWithForwardScattering) {
  // Translucent white spheres over a floor, seen from above, with a forward
  // phase function: the scattering visibly lightens and softens the shadows.
  Scene scene = floored_spheres();
  scene.set_transfer_function(testing::step_tf(0.2f, vec3(1.0f), 0.15f));
  Camera camera = scene.camera();
  camera.eye = vec3(0.0f, -60.0f, 150.0f);
  camera.target = vec3(0.0f, 0.0f, -20.0f);
  camera.fov_deg = 40.0f;
  scene.set_camera(camera);
  Material m = scene.material();
  m.phase_g = 0.6f;
  scene.set_material(m);
  const ParameterSettings params = {{"albedo", 0.8}, {"cone_angle_deg", 30.0}};
  const Image ipsvi = render_with(scene, "ipsvi", params);
  const Image half = render_with(scene, "half-angle", params);
  const Image single = render_with(scene, "ipsvi");
  save_test_image(ipsvi, "fig8-spheres-ipsvi.png");
  save_test_image(half, "fig8-spheres-half-angle.png");
  const double de = mean_de(ipsvi, half), effect = mean_de(ipsvi, single);
  std::printf("spheres, albedo 0.8: ipsvi vs half-angle mean dE %.3f (scattering itself changes %.3f)\n", de, effect);
  EXPECT_LT(de, 0.5);
  EXPECT_LT(de, 0.5 * effect);
}

TEST(HalfAngleVersusIpsvi, AgreeOnTheEngine) {
  if (!std::filesystem::exists(std::filesystem::path(PENUMBRA_SHARED_DATA_DIR) / "engine_256x256x128_uint8.nhdr")) {
    GTEST_SKIP() << "the engine CT is not in " << PENUMBRA_SHARED_DATA_DIR;
  }
  Scene scene = load_scene(std::filesystem::path(PENUMBRA_SOURCE_DIR) / "scenes" / "engine.json");
  RenderSettings r = scene.render();
  r.width = r.height = 64;
  scene.set_render(r);
  const Image reference = render_with(scene, "shadow-rays");
  for (const double albedo : {0.0, 0.5}) {
    const Image ipsvi = render_with(scene, "ipsvi", {{"albedo", albedo}});
    // A light buffer of about one texel per voxel (the image's 64 texels
    // would be six voxels wide); ipsvi's cache is the size of the pixels but
    // its light segments are marched at the sample, so it needs no more.
    const Image half = render_with(scene, "half-angle", {{"albedo", albedo}, {"light_buffer_size", 256.0}});
    if (albedo > 0.0) {
      save_test_image(ipsvi, "fig8-engine-ipsvi.png");
      save_test_image(half, "fig8-engine-half-angle.png");
    }
    const DeltaEStats de = delta_e_stats(ipsvi, half);
    std::printf("engine, albedo %.1f: ipsvi vs half-angle mean dE %.3f, p99 %.3f; vs shadow-rays %.3f / %.3f\n",
                albedo, de.mean, de.p99, mean_de(ipsvi, reference), mean_de(half, reference));
    // The paper's claim: the two agree to under 1 dE on average (observed
    // 0.82-0.86; their residual errors sit at different shadow edges).
    EXPECT_LT(de.mean, 1.0);
  }
}

TEST(SliceGeometry, HalfAngleAxisKeepsBothOrders) {
  Camera camera;
  camera.eye = vec3(0.0f, -100.0f, 20.0f);
  camera.target = vec3(0.0f);
  const CameraView view = camera.view();
  const Box3 box{vec3(-10.0f, -20.0f, -5.0f), vec3(10.0f, 20.0f, 5.0f)};
  for (const vec3& direction : {vec3(0.3f, 0.9f, -0.5f), vec3(0.2f, -1.0f, -0.3f), vec3(1.0f, 0.0f, 0.0f),
                               vec3(0.0f, 1.0f, 0.0f), vec3(0.0f, -1.0f, 0.0f)}) {
    Light light;
    light.direction = glm::normalize(direction);
    const SliceSetup s = make_slice_setup(view, light, box, 0, 0.5f);
    EXPECT_NEAR(glm::length(s.axis), 1.0f, 1e-5f);
    EXPECT_GT(glm::dot(s.axis, light.direction), 0.0f) << "the light advances with the slices";
    EXPECT_EQ(s.eye_front_to_back, glm::dot(view.forward, light.direction) >= 0.0f);
    // Along s the eye moves forward (front to back) or backward (flipped).
    EXPECT_EQ(glm::dot(s.axis, view.forward) > 0.0f, s.eye_front_to_back);
    // The slices span the box, half a spacing in from its extremes, and the
    // central viewing ray crosses one per step.
    float lo = kInfinity, hi = -kInfinity;
    for (int i = 0; i < 8; ++i) {
      const vec3 c(i & 1 ? box.upper.x : box.lower.x, i & 2 ? box.upper.y : box.lower.y,
                   i & 4 ? box.upper.z : box.lower.z);
      lo = std::min(lo, glm::dot(s.axis, c));
      hi = std::max(hi, glm::dot(s.axis, c));
    }
    EXPECT_NEAR(s.position(0), lo + 0.5f * s.spacing, 1e-3f);
    EXPECT_NEAR(s.position(s.count - 1), hi - 0.5f * s.spacing, 1e-3f);
    EXPECT_LE(s.spacing / std::abs(glm::dot(s.axis, view.forward)), 0.5f + 1e-4f);
    // Each cut through the box lies on its plane and inside the box.
    vec3 polygon[12];
    const int n = slice_polygon(box, s.axis, s.position(s.count / 2), polygon);
    EXPECT_GE(n, 3);
    for (int i = 0; i < n; ++i) {
      EXPECT_NEAR(glm::dot(s.axis, polygon[i]), s.position(s.count / 2), 1e-3f);
      const Box3 grown{box.lower - vec3(1e-3f), box.upper + vec3(1e-3f)};
      EXPECT_TRUE(grown.contains(polygon[i]));
    }
  }
  Light light;
  EXPECT_EQ(make_slice_setup(view, light, box, 37, 0.5f).count, 37);
}

}  // namespace
}  // namespace penumbra

// ipsvi against shadow-rays (its albedo-0 limit: the same single-scattering
// model, so the difference is the cache's interpolation), and the relations
// the paper and the issue state: the cache's memory does not grow with the
// data, the ERT extension changes the work but not the image, point-light
// zones blend without seams, piecewise integration is what makes wide lines
// and off-screen occluders work.
//
// Tolerances are mean CIEDE2000 against shadow-rays unless said otherwise,
// about 3x the measured values (written beside them), so that a reversed
// sweep, a plain early termination instead of the ERT extension or a wrong
// zone boundary fails (each tried, issue 21). One
// dE unit is about a just-noticeable difference; the cache is bilinear in
// light space with texels of about one voxel, so shadow edges move by up to a
// texel, which on these 48^3 scenes is a few dE on the edge pixels and a mean
// well below 1 over the image.
#include "penumbra/analysis/image_metrics.h"
#include "penumbra/backends/cpu/packets.h"
#include "penumbra/base/error.h"
#include "penumbra/render/scene_resources.h"
#include "penumbra/techniques/ipsvi/early_termination.h"
#include "penumbra/techniques/ipsvi/sweep_plan.h"
#include "penumbra/techniques/ipsvi/sweep_renderer.h"
#include "penumbra/techniques/registry.h"
#include "test_scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace penumbra {
namespace {

using testing::lit_spheres;
using testing::procedural_scene;
using testing::render_with;
using testing::save_test_image;
using testing::with_floor;

struct Rendered {
  Image image;
  IpsviFrameCounts counts;
};

Rendered render_ipsvi(const Scene& scene, IpsviSettings settings = {}) {
  IpsviRenderer r;
  r.prepare(scene, settings);
  Rendered out;
  r.render(scene, out.image);
  out.counts = r.last_counts();
  return out;
}

using testing::mean_de;

// Light-segment samples (at the viewing-ray samples and at the cache writes)
// per viewing-ray sample: what the sweep saves over shadow rays, bounded at
// about 1.5x the measured value so that a change that leaves texels unwritten
// (and falls back to long segments) shows. (A reversed sweep does the
// opposite: its texels are ahead of the samples, which take them as they
// are; the dE bounds catch that: mean 0.24-0.44 on the point lights.)
double light_work(const IpsviFrameCounts& c) {
  return double(c.light_samples + c.write_samples) / double(std::max<std::uint64_t>(c.view_samples, 1));
}

TEST(Ipsvi, AlbedoZeroMatchesShadowRaysOnTheSpheres) {
  const Scene scene = with_floor(lit_spheres());
  const Image reference = render_with(scene, "shadow-rays");
  const Image ipsvi = render_with(scene, "ipsvi");
  save_test_image(reference, "ipsvi-spheres-shadow-rays.png");
  save_test_image(ipsvi, "ipsvi-spheres.png");
  const DeltaEStats de = delta_e_stats(ipsvi, reference);
  std::printf("ipsvi vs shadow-rays, spheres + floor: mean dE %.4f, p99 %.3f\n", de.mean, de.p99);
  // Measured 0.0088 / 0.182 (0.029 / 0.748 before floor points on shadow
  // edges marched their own light ray, 0.054 / 1.22 before the cache trailed
  // its writers).
  EXPECT_LT(de.mean, 0.027);
  EXPECT_LT(de.p99, 0.55);
}

// Light from behind the volume (travelling toward the camera): rays are
// traversed back to front, the sweep runs outward from the light's vanishing
// point.
TEST(Ipsvi, BacklitMatchesShadowRays) {
  Scene scene = lit_spheres();
  Light light;
  light.direction = glm::normalize(vec3(0.3f, -1.0f, -0.4f));
  scene.set_lights({light});
  const double de = mean_de(render_with(scene, "ipsvi"), render_with(scene, "shadow-rays"));
  std::printf("backlit: mean dE %.4f\n", de);
  EXPECT_LT(de, 0.015);  // measured 0.005 (0.057 before the cache trailed its writers)
}

// The cache is a light-space image of cache_size^2 texels, whatever the data.
TEST(Ipsvi, CacheMemoryDoesNotGrowWithTheData) {
  auto bytes_for = [](int n) {
    Scene scene;
    auto volume = std::make_shared<Volume>(ivec3(n), VoxelType::UInt8);
    std::fill_n(volume->frame_as<std::uint8_t>(0), volume->voxel_count(), std::uint8_t(0));
    volume->frame_as<std::uint8_t>(0)[0] = 255;
    scene.set_volume(volume);
    scene.set_camera(Camera::framing(scene.volume().world_box()));
    RenderSettings r;
    r.width = r.height = 16;
    scene.set_render(r);
    scene.set_lights({Light{}});
    IpsviSettings settings;
    settings.early_termination = true;
    settings.cache_size = 256;  // the automatic size follows the image, not the data
    IpsviRenderer renderer;
    renderer.prepare(scene, settings);
    Image image;
    renderer.render(scene, image);
    return renderer.aux_bytes();
  };
  const std::uint64_t small = bytes_for(64), large = bytes_for(256);
  EXPECT_EQ(small, large);
  EXPECT_GT(small, 256u * 256u * 8u);  // at least the cache's (transmittance, depth) texels
}

// The ERT extension (section 5.1). A homogeneous opaque slab lit from the
// camera's side: rays stop a few voxels in, soon after their colour is done,
// so the samples drop while the image stays within 0.05 mean dE (the
// pre-pass is conservative, so this is rounding, not missing light).
TEST(Ipsvi, EarlyTerminationKeepsTheImageWithFewerSamples) {
  Scene scene = procedural_scene("slab", ivec3(48), 48);
  scene.set_transfer_function(testing::step_tf(0.0f, vec3(0.9f, 0.7f, 0.5f), 0.5f));
  Light light;
  light.direction = glm::normalize(vec3(0.4f, 0.8f, -0.6f));
  scene.set_lights({light});
  const Rendered full = render_ipsvi(scene);
  IpsviSettings ert;
  ert.early_termination = true;
  const Rendered early = render_ipsvi(scene, ert);
  const DeltaEStats de = delta_e_stats(early.image, full.image);
  auto all = [](const IpsviFrameCounts& c) {
    return c.view_samples + c.light_samples + c.write_samples + c.prepass_samples;
  };
  const std::uint64_t without = all(full.counts), with = all(early.counts);
  std::printf("ERT on a slab: mean dE %.4f, max %.3f; view samples %llu -> %llu, all samples %llu -> %llu\n",
              de.mean, de.max, (unsigned long long)full.counts.view_samples,
              (unsigned long long)early.counts.view_samples, (unsigned long long)without, (unsigned long long)with);
  EXPECT_LT(de.mean, 0.005);  // measured 0
  EXPECT_LT(early.counts.view_samples, full.counts.view_samples / 2);
  EXPECT_LT(with, without * 2 / 3);
  // With piecewise integration the cache stays right whatever the rays
  // sample (an unwritten texel marches to the box), so a plain early
  // termination would keep the image too, at the price of long light
  // segments. Without it the cache holds only what the rays wrote: the
  // extension must keep the rays that carry hidden casters' shadows.
  IpsviSettings no_pi;
  no_pi.piecewise_integration = false;
  const Rendered full_no_pi = render_ipsvi(scene, no_pi);
  no_pi.early_termination = true;
  const Rendered early_no_pi = render_ipsvi(scene, no_pi);
  const DeltaEStats de_no_pi = delta_e_stats(early_no_pi.image, full_no_pi.image);
  auto segments = [](const IpsviFrameCounts& c) { return double(c.light_samples + c.write_samples); };
  std::printf("ERT without PI: mean dE %.4f, p99 %.3f; light samples with PI %.0f -> %.0f\n", de_no_pi.mean,
              de_no_pi.p99, segments(full.counts), segments(early.counts));
  EXPECT_LT(de_no_pi.mean, 0.05);
  EXPECT_LT(de_no_pi.p99, 1.0);
  EXPECT_LT(segments(early.counts), 0.9 * segments(full.counts)) << "stopped rays must not leave long light segments";
}

// Fig. 5: what a ray's opaque front hides may shadow what other rays see.
// Spheres in front of each other, lit from the side, over a floor: the sweep
// toward the light must push some exits past the pre-pass's own ERT depth, and
// the image must stay that of the full march.
TEST(Ipsvi, EarlyTerminationKeepsWhatShadowsOtherRays) {
  Scene scene = with_floor(lit_spheres(64));
  scene.set_transfer_function(testing::step_tf(0.2f, vec3(0.9f, 0.7f, 0.5f), 0.6f));
  Light light;
  light.direction = glm::normalize(vec3(1.0f, 0.3f, -0.5f));
  scene.set_lights({light});
  const Rendered full = render_ipsvi(scene);
  IpsviSettings ert;
  ert.early_termination = true;
  const Rendered early = render_ipsvi(scene, ert);
  save_test_image(full.image, "ipsvi-ert-off.png");
  save_test_image(early.image, "ipsvi-ert-on.png");
  const DeltaEStats de = delta_e_stats(early.image, full.image);
  std::printf("ERT on spheres: mean dE %.4f, p99 %.3f; view samples %llu -> %llu\n", de.mean, de.p99,
              (unsigned long long)full.counts.view_samples, (unsigned long long)early.counts.view_samples);
  EXPECT_LT(de.mean, 0.005);  // measured 0
  EXPECT_LT(de.p99, 0.05);
  EXPECT_LT(early.counts.view_samples, full.counts.view_samples);
  // Without piecewise integration nothing but the rays' writes carries the
  // hidden spheres' shadows.
  IpsviSettings no_pi;
  no_pi.piecewise_integration = false;
  const Rendered full_no_pi = render_ipsvi(scene, no_pi);
  no_pi.early_termination = true;
  const DeltaEStats de_no_pi = delta_e_stats(render_ipsvi(scene, no_pi).image, full_no_pi.image);
  std::printf("ERT on spheres without PI: mean dE %.4f, p99 %.3f\n", de_no_pi.mean, de_no_pi.p99);
  // Measured 0 (the pre-pass is conservative); a plain early termination
  // gives mean 0.003, p99 0.02.
  EXPECT_LT(de_no_pi.mean, 0.0005);
  EXPECT_LT(de_no_pi.p99, 0.005);

  SceneResources resources;
  resources.update(scene);
  const RenderView view = resources.view(scene);
  EarlyTermination maps;
  maps.compute(view, light, project_light(view.camera, 64, 64, light), PixelRect{0, 0, 64, 64});
  int extended = 0;
  for (std::size_t i = 0; i < maps.needed().size(); ++i) {
    if (!std::isfinite(maps.front()[i])) continue;
    EXPECT_LE(maps.needed()[i], maps.back()[i]) << "never past the last structure";
    extended += maps.needed()[i] > maps.front()[i] + 1.0f;
  }
  EXPECT_GT(extended, 3) << "the sweep toward the light extends rays that hide shadow casters";
}

// A point light in front of the camera, inside the image: four zones meet at
// s'_l along the diagonals. A seam would show as a jump between neighbouring
// pixels on opposite sides of a zone border that shadow-rays (no zones) does
// not have. Measured over every such pair: the mean of |jump(ipsvi) -
// jump(shadow-rays)| must be no larger than over pairs away from the borders
// (times 1.5) and small in absolute terms.
TEST(Ipsvi, PointLightZonesBlendWithoutSeams) {
  Scene scene = with_floor(lit_spheres(64));
  Light light;
  light.type = LightType::Point;
  light.position = vec3(5.0f, -90.0f, 12.0f);
  light.intensity = 5000.0f;
  scene.set_lights({light});
  const Image reference = render_with(scene, "shadow-rays");
  const Rendered rendered = render_ipsvi(scene);
  const Image& ipsvi = rendered.image;
  std::printf("zones: light work %.2f\n", light_work(rendered.counts));
  EXPECT_LT(light_work(rendered.counts), 12.5);  // measured 8.46 (7.71 before floor edges marched)
  save_test_image(reference, "ipsvi-point-shadow-rays.png");
  save_test_image(ipsvi, "ipsvi-point.png");
  const ImageLight il = project_light(scene.camera().view(), 64, 64, light);
  ASSERT_EQ(int(il.flow), int(LightFlow::Outward));
  ASSERT_TRUE(il.position.x > 8 && il.position.x < 56 && il.position.y > 8 && il.position.y < 56)
      << "the test needs s'_l inside the image";
  auto zone = [&](int x, int y) {  // 0: x zones, 1: y zones
    const vec2 d = vec2(x, y) + 0.5f - il.position;
    return std::abs(d.x) >= std::abs(d.y) ? 0 : 1;
  };
  double border = 0.0, inner = 0.0;
  int border_pairs = 0, inner_pairs = 0;
  for (int y = 0; y + 1 < 64; ++y) {
    for (int x = 0; x + 1 < 64; ++x) {
      for (const ivec2& step : {ivec2(1, 0), ivec2(0, 1)}) {
        const int x2 = x + step.x, y2 = y + step.y;
        const float jump_i = luminance(vec3(ipsvi.at(x2, y2))) - luminance(vec3(ipsvi.at(x, y)));
        const float jump_r = luminance(vec3(reference.at(x2, y2))) - luminance(vec3(reference.at(x, y)));
        const double e = std::abs(jump_i - jump_r);
        if (zone(x, y) != zone(x2, y2)) {
          border += e;
          ++border_pairs;
        } else {
          inner += e;
          ++inner_pairs;
        }
      }
    }
  }
  border /= border_pairs;
  inner /= inner_pairs;
  std::printf("zone seams: border %.5f (%d pairs), elsewhere %.5f; mean dE %.4f\n", border, border_pairs, inner,
              mean_de(ipsvi, reference));
  EXPECT_GT(border_pairs, 60);
  EXPECT_LT(border, 1.5 * inner + 1e-3);
  EXPECT_LT(border, 0.01);
  EXPECT_LT(mean_de(ipsvi, reference), 0.013);  // measured 0.0043 (0.007 before floor edges marched)
}

// Point lights in front of the volume (between it and the camera), behind
// it (facing the camera) and inside it (octahedral cache; rays split at the
// light's closest approach and traversed away from it on both sides).
TEST(Ipsvi, PointLightsInFrontBehindAndInsideMatchShadowRays) {
  Scene scene = lit_spheres();
  const vec3 eye = scene.camera().eye;  // on -y, looking along +y
  struct Case {
    vec3 position;
    double max_de, max_work;  // about 3x the measured dE, 1.5x the measured work
  };
  // Measured dE 0.014, 0.009, 0.005, 0.006 and work 1.92, 8.98, 14.98, 14.91
  // (dE 0.013-0.04 before the cache trailed its writers).
  for (const Case& c : {Case{vec3(0.4f, 0.45f, 0.1f) * eye, 0.04, 2.9}, Case{vec3(5.0f, 60.0f, 8.0f), 0.03, 13.5},
                        Case{vec3(2.0f, -3.0f, 4.0f), 0.015, 22.5},
                        Case{scene.volume().world_box().center(), 0.02, 22.5}}) {
    Light light;
    light.type = LightType::Point;
    light.position = c.position;
    light.intensity = 200.0f + glm::dot(c.position, c.position);
    scene.set_lights({light});
    const Rendered r = render_ipsvi(scene);
    for (const vec4& p : r.image.pixels()) ASSERT_TRUE(std::isfinite(p.r) && std::isfinite(p.g) && std::isfinite(p.b));
    const double de = mean_de(r.image, render_with(scene, "shadow-rays"));
    std::printf("point light at (%.0f, %.0f, %.0f): mean dE %.3f, light work %.2f\n", c.position.x, c.position.y,
                c.position.z, de, light_work(r.counts));
    EXPECT_LT(de, c.max_de);
    EXPECT_LT(light_work(r.counts), c.max_work);
  }
}

// A light inside the box, out of view: its octahedral map holds only the
// directions toward what the camera sees of the box (cache_fit.h). A visible
// floor point may lie in another direction, with its light ray through a
// part of the box the camera does not see (here a haze fills the box); it
// marches that ray (plane_light), as shadow-rays does, instead of reading
// the cache as unshadowed.
TEST(Ipsvi, FloorOutsideAFittedOctahedralMapKeepsItsShadows) {
  Scene scene = with_floor(lit_spheres(64));
  scene.set_transfer_function(testing::step_tf(0.0f, vec3(0.8f), 0.03f));
  const Box3 box = scene.volume().world_box();
  Light light;
  light.type = LightType::Point;
  light.position = box.center() + vec3(0.3f, 0.3f, 0.35f) * box.extent();
  light.intensity = 400.0f;
  scene.set_lights({light});
  Camera camera = scene.camera();
  // The box's lower corner far from the light and the floor around it.
  camera.target = vec3(box.lower.x + 4.0f, box.lower.y + 4.0f, box.lower.z - 4.0f);
  camera.eye = camera.target + vec3(-0.5f, -0.8f, 0.9f) * glm::length(box.extent());
  camera.up = vec3(0.0f, 0.0f, 1.0f);
  camera.fov_deg = 30.0f;
  scene.set_camera(camera);
  const std::vector<LightCacheProjection> fits = fit_ipsvi_caches(scene, IpsviSettings{});
  ASSERT_EQ(fits.size(), 1u);
  ASSERT_EQ(fits[0].mapping, LightMapping::Octahedral);
  const Rendered r = render_ipsvi(scene);
  const Image reference = render_with(scene, "shadow-rays", {{"shadow_cache", false}});
  save_test_image(r.image, "ipsvi-octahedral-floor.png");
  save_test_image(reference, "ipsvi-octahedral-floor-reference.png");
  const double de = mean_de(r.image, reference);
  std::printf("map %d x %d (%s), floor points that marched their light ray: %llu, mean dE %.4f\n", fits[0].size,
              fits[0].rows, fits[0].lower == vec2(0.0f) ? "whole" : "part", (unsigned long long)r.counts.exact_plane_rays,
              de);
  // Measured: 184 floor points marched, mean dE 0.0002; read as unshadowed
  // they were 13 and 0.086.
  EXPECT_NE(fits[0].lower, vec2(0.0f)) << "a part of the map";
  EXPECT_GT(r.counts.exact_plane_rays, 100u);
  EXPECT_LT(de, 0.001);
}

// The automatic cache size for a light inside the box: texels must stay about
// a pixel wide out to the box's corners however close the light is to the
// centre (measured at the centre distance, a light at the centre got the
// 16^2 minimum and leaked light in radial streaks: engine CT at 160^2, mean
// dE 4.3 against shadow-rays, 0.11 with this size).
TEST(Ipsvi, CacheSizeForALightAtTheCentreCoversTheBox) {
  Scene scene = lit_spheres(64);
  const Box3 box = scene.volume().world_box();
  auto size_at = [&](vec3 position) {
    Light light;
    light.type = LightType::Point;
    light.position = position;
    scene.set_lights({light});
    return ipsvi_cache_size(scene, IpsviSettings{});
  };
  const int centre = size_at(box.center());
  const int off_centre = size_at(box.center() + 0.3f * box.extent());
  std::printf("cache size, light at the centre: %d, off-centre: %d\n", centre, off_centre);
  EXPECT_EQ(centre, off_centre) << "the size must not collapse as the light nears the centre";
  const Camera& c = scene.camera();
  const float pixel = 2.0f * std::tan(0.5f * glm::radians(c.fov_deg)) * glm::length(box.center() - c.eye) / 64.0f;
  // sqrt(4 pi) r / n: the octahedral texel's mean width at the half-diagonal r.
  EXPECT_LE(3.5449077f * 0.5f * glm::length(box.extent()) / float(centre), 1.01f * pixel);
}

// Light along the view direction (4.4): with a perspective camera the
// vanishing point is the image centre and four zones meet there; with an
// orthographic camera every light ray is a viewing ray and the light is
// carried along the ray itself. Both from the front (headlight) and from
// behind the volume (the light faces the camera).
TEST(Ipsvi, LightAlongTheViewDirectionMatchesShadowRays) {
  // About 3x the measured mean dE, per camera, light side and piecewise
  // integration (on, off): perspective headlight 0.023, 0.103; facing 0.057,
  // 0.422; orthographic headlight 0.004, 0.068; facing 0.006, 0.219.
  const double bounds[2][2][2] = {{{0.07, 0.3}, {0.17, 1.2}}, {{0.015, 0.2}, {0.02, 0.65}}};
  for (const bool orthographic : {false, true}) {
    for (const float sign : {1.0f, -1.0f}) {
      Scene scene = lit_spheres();
      Camera camera = scene.camera();
      if (orthographic) {
        camera.projection = Projection::Orthographic;
        camera.ortho_height = 90.0f;
        scene.set_camera(camera);
      }
      Light light;
      light.direction = sign * glm::normalize(camera.target - camera.eye);
      scene.set_lights({light});
      for (const bool piecewise : {true, false}) {
        IpsviSettings settings;
        settings.piecewise_integration = piecewise;
        const double de = mean_de(render_ipsvi(scene, settings).image, render_with(scene, "shadow-rays"));
        std::printf("light along view (%s, %s, PI %d): mean dE %.3f\n", orthographic ? "ortho" : "persp",
                    sign > 0 ? "headlight" : "facing", int(piecewise), de);
        EXPECT_LT(de, bounds[orthographic][sign < 0.0f][!piecewise]);
      }
    }
  }
}

// Volume partly off screen: a camera zoomed onto one sphere while another,
// off screen, shadows the floor beside it. With piecewise integration an
// unwritten cache texel marches to the box, so the off-screen sphere still
// casts its shadow; without it, as in the paper (section 7), it does not.
TEST(Ipsvi, OffScreenStructuresShadowOnlyWithPiecewiseIntegration) {
  Scene scene = with_floor(lit_spheres(48));
  Light light;
  light.direction = glm::normalize(vec3(1.0f, 0.0f, -1.0f));
  scene.set_lights({light});
  Camera camera = scene.camera();
  camera.eye = vec3(20.0f, -70.0f, 10.0f);
  camera.target = vec3(18.0f, 0.0f, -20.0f);
  camera.fov_deg = 25.0f;
  scene.set_camera(camera);
  const Image reference = render_with(scene, "shadow-rays");
  const Image with_pi = render_with(scene, "ipsvi");
  const Image without_pi = render_with(scene, "ipsvi", {{"piecewise_integration", false}});
  save_test_image(reference, "ipsvi-offscreen-shadow-rays.png");
  save_test_image(with_pi, "ipsvi-offscreen-pi.png");
  save_test_image(without_pi, "ipsvi-offscreen-no-pi.png");
  const double de_pi = mean_de(with_pi, reference), de_no_pi = mean_de(without_pi, reference);
  std::printf("off screen: mean dE with PI %.4f, without %.3f\n", de_pi, de_no_pi);
  EXPECT_LT(de_pi, 0.015);  // measured 0.0049, 6.75 without PI (0.046 before floor edges marched)
  EXPECT_GT(de_no_pi, 3.0 * de_pi);
}

// Section 4.4 and Fig. 9: without piecewise integration a sample adds only its
// own step to the light, so wider lines (more depth between cache updates)
// and distant cameras (more depth per pixel) lose shadow; with it, the line
// width changes the image little.
TEST(Ipsvi, PiecewiseIntegrationKeepsWideLinesAndSmallImagesRight) {
  const Scene scene = with_floor(lit_spheres(48));
  const Image reference = render_with(scene, "shadow-rays");
  const double pi_1 = mean_de(render_with(scene, "ipsvi", {{"line_width", 1.0}}), reference);
  const double pi_8 = mean_de(render_with(scene, "ipsvi", {{"line_width", 8.0}}), reference);
  const double no_pi_1 =
      mean_de(render_with(scene, "ipsvi", {{"line_width", 1.0}, {"piecewise_integration", false}}), reference);
  const double no_pi_8 =
      mean_de(render_with(scene, "ipsvi", {{"line_width", 8.0}, {"piecewise_integration", false}}), reference);
  std::printf("line width 1 / 8: with PI %.4f / %.4f, without %.3f / %.3f\n", pi_1, pi_8, no_pi_1, no_pi_8);
  EXPECT_LT(pi_8, 0.0006);  // measured 0.0002 (0.014 before floor edges marched)
  EXPECT_GT(no_pi_8, no_pi_1);
  EXPECT_GT(no_pi_1, 2.0 * pi_1);
  Scene small = scene;  // a distant camera: the same view at a quarter of the pixels
  RenderSettings r = small.render();
  r.width = r.height = 16;
  small.set_render(r);
  const Image small_reference = render_with(small, "shadow-rays");
  const double small_pi = mean_de(render_with(small, "ipsvi"), small_reference);
  const double small_no_pi = mean_de(render_with(small, "ipsvi", {{"piecewise_integration", false}}), small_reference);
  std::printf("16^2: with PI %.4f, without %.3f\n", small_pi, small_no_pi);
  EXPECT_LT(small_pi, 0.0006);  // measured 0.0002, 1.25 without PI (0.007 before floor edges marched)
  EXPECT_GT(small_no_pi, 1.0);
}

// Light-space work uses the scene's shadow TF (a lighter one here), clip
// planes cut what casts shadows, and Phong shading takes the same
// visibility: all as shadow-rays does.
TEST(Ipsvi, ShadowTransferFunctionClipPlanesAndPhongAsShadowRays) {
  Scene scene = with_floor(lit_spheres());
  scene.set_shadow_transfer_function(testing::step_tf(0.2f, vec3(1.0f), 0.05f));
  scene.set_clip_planes({vec4(0.3f, 0.0f, 1.0f, 4.0f)});
  Material m = scene.material();
  m.shading = Shading::Phong;
  scene.set_material(m);
  const Rendered r = render_ipsvi(scene);
  const Image& image = r.image;
  const double de = mean_de(image, render_with(scene, "shadow-rays"));
  std::printf("shadow TF + clip plane: light work %.2f\n", light_work(r.counts));
  EXPECT_LT(light_work(r.counts), 7.5);  // measured 4.9 (3.0 before the cache trailed its writers, issue 21)
  Scene same_tf = scene;
  same_tf.set_shadow_transfer_function(std::nullopt);
  const double shadow_tf_effect = mean_de(image, render_with(same_tf, "ipsvi"));
  std::printf("shadow TF + clip plane + phong: mean dE %.4f (the shadow TF itself changes %.3f)\n", de,
              shadow_tf_effect);
  // Measured 0.0002 (0.002 before floor edges marched their own light ray,
  // 0.009 before the cache trailed its writers).
  EXPECT_LT(de, 0.0006);
  EXPECT_GT(shadow_tf_effect, 5.0 * de);
}

// Several lights: one sweep each, added; the same as shadow-rays with both.
TEST(Ipsvi, TwoLightsAddUp) {
  Scene scene = lit_spheres();
  Light a, b;
  a.direction = glm::normalize(vec3(0.5f, 0.7f, -1.0f));
  b.type = LightType::Point;
  b.position = vec3(-60.0f, -40.0f, 10.0f);
  b.intensity = 3000.0f;
  b.color = vec3(0.3f, 0.5f, 1.0f);
  scene.set_lights({a, b});
  const double de = mean_de(render_with(scene, "ipsvi"), render_with(scene, "shadow-rays"));
  std::printf("two lights: mean dE %.4f\n", de);
  EXPECT_LT(de, 0.035);  // measured 0.0110
}

// The forward-scattering part (albedo > 0): with a cone of 0 degrees it is
// exactly the direct light, so the image does not change; with a cone and a
// forward phase function a translucent white medium lets more light through,
// and its shadow on the floor (seen from above) gets lighter.
TEST(Ipsvi, ForwardScatteringLightensShadowsAndReducesToSingleScatteringWithoutACone) {
  Scene scene = with_floor(lit_spheres());
  scene.set_transfer_function(testing::step_tf(0.2f, vec3(1.0f), 0.15f));
  Camera camera = scene.camera();
  camera.eye = vec3(0.0f, -60.0f, 150.0f);
  camera.target = vec3(0.0f, 0.0f, -20.0f);
  camera.fov_deg = 40.0f;
  scene.set_camera(camera);
  const Image single = render_with(scene, "ipsvi");
  const Image no_cone = render_with(scene, "ipsvi", {{"albedo", 0.8}, {"cone_angle_deg", 0.0}});
  EXPECT_LT(mean_de(no_cone, single), 0.2);
  Material m = scene.material();
  m.phase_g = 0.6f;
  scene.set_material(m);
  const Image g_single = render_with(scene, "ipsvi");
  const Image scattered = render_with(scene, "ipsvi", {{"albedo", 0.8}, {"cone_angle_deg", 30.0}});
  save_test_image(g_single, "ipsvi-translucent.png");
  save_test_image(scattered, "ipsvi-translucent-albedo.png");
  // Shadowed pixels: darker than half the lit floor (the brightest tenth).
  std::vector<float> lum;
  for (const vec4& p : g_single.pixels()) lum.push_back(luminance(vec3(p)));
  std::vector<float> sorted = lum;
  std::sort(sorted.begin(), sorted.end());
  const float lit = sorted[sorted.size() * 9 / 10];
  double before = 0.0, after = 0.0;
  int shadowed = 0;
  for (std::size_t i = 0; i < lum.size(); ++i) {
    if (g_single.pixels()[i].a < 0.99f || lum[i] > 0.5f * lit) continue;
    before += lum[i];
    after += luminance(vec3(scattered.pixels()[i]));
    ++shadowed;
  }
  std::printf("forward scattering: %d shadowed pixels, mean luminance %.4f -> %.4f\n", shadowed,
              before / std::max(shadowed, 1), after / std::max(shadowed, 1));
  EXPECT_GT(shadowed, 50);
  EXPECT_GT(after, 1.2 * before);
}

// A ray records at most a tape's worth of light segments for the packets
// (segment_tape.h); the rest it marches itself while replaying, and the
// resolve step's chunks do the same. With a tape of 16 the spheres' rays and
// chunks overflow it: the same image as with a tape that holds them all, with
// fewer segments as packets (3835 against 6983 at albedo 0).
TEST(Ipsvi, SegmentsBeyondTheTapeAreMarchedOneAtATime) {
  if (active_simd_target() == SimdTarget::Scalar) GTEST_SKIP() << "no SIMD target: no packets";
  const Scene scene = with_floor(lit_spheres());
  IpsviSettings small;
  small.segment_tape_limit = 16;
  for (const float albedo : {0.0f, 0.5f}) {
    IpsviSettings full;
    full.albedo = small.albedo = albedo;
    const Rendered all = render_ipsvi(scene, full);
    const Rendered some = render_ipsvi(scene, small);
    EXPECT_GT(some.counts.packet_segments, 0u);
    EXPECT_LT(double(some.counts.packet_segments), 0.7 * double(all.counts.packet_segments));
    EXPECT_LE(rmse(some.image, all.image), 1e-6) << albedo;
  }
}

TEST(Ipsvi, RebuildsOnlyWhenLightsDataClipPlanesOrCacheSizeChange) {
  Scene scene = lit_spheres(24);
  const TechniqueInfo& info = find_technique("ipsvi");
  ParameterValues params(info.parameters);
  auto t = info.create();
  t->prepare(scene, params);
  EXPECT_EQ(t->rebuilds(), 1u);
  Camera camera = scene.camera();
  camera.orbit(20.0f, 5.0f);
  scene.set_camera(camera);
  scene.set_transfer_function(testing::step_tf(0.3f, vec3(1.0f), 0.4f));
  scene.set_material(Material{});
  params.set("line_width", 4.0);
  t->prepare(scene, params);
  EXPECT_EQ(t->rebuilds(), 1u) << "camera, TF, material and line width need no new cache";
  scene.set_lights(scene.lights());
  t->prepare(scene, params);
  EXPECT_EQ(t->rebuilds(), 2u);
  scene.set_clip_planes({vec4(0.0f, 0.0f, 1.0f, 5.0f)});
  t->prepare(scene, params);
  EXPECT_EQ(t->rebuilds(), 3u);
  params.set("cache_size", 64.0);
  t->prepare(scene, params);
  EXPECT_EQ(t->rebuilds(), 4u);
  Image image;
  t->render(scene, image);
  EXPECT_EQ(image.width(), 24);
}

TEST(Ipsvi, BadParametersNameTheParameter) {
  const TechniqueInfo& info = find_technique("ipsvi");
  ParameterValues params(info.parameters);
  for (const auto& [name, value] : std::vector<std::pair<std::string, double>>{
           {"cache_size", 8000.0}, {"line_width", 0.0}, {"albedo", 1.5}, {"cone_angle_deg", 90.0}}) {
    try {
      params.set(name, value);
      ADD_FAILURE() << name << " accepted " << value;
    } catch (const InvalidArgument& e) {
      EXPECT_EQ(e.name(), name);
    }
  }
  // 1..15 pass the table's range but not prepare (0 means automatic).
  params.set("cache_size", 8.0);
  auto t = info.create();
  try {
    t->prepare(lit_spheres(16), params);
    ADD_FAILURE() << "cache_size 8 accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.name(), "cache_size");
  }
}

}  // namespace
}  // namespace penumbra

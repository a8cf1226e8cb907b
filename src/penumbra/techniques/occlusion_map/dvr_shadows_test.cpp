// occlusion-map's DVR mode with soft shadows (one grid per light, marched
// through the moment pyramid): shadows where the geometry puts them, penumbrae
// that follow the light's size, what rebuilds the grids, and the parameter
// rule.
#include "penumbra/analysis/image_metrics.h"
#include "penumbra/backends/cpu/packets.h"
#include "penumbra/base/error.h"
#include "penumbra/techniques/registry.h"
#include "penumbra/volume/procedural.h"
#include "test_scene.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <optional>
#include <tuple>

namespace penumbra {
namespace {

using testing::antialiased_solid;
using testing::procedural_scene;
using testing::render_with;

struct Ball {
  vec3 centre;
  float radius;
};
// A big ball lit from above and a small one between it and the light, both
// opaque under a step TF at 0.5 (the iso-value), spacing 1, the volume
// centred on the origin.
const Ball kBig{vec3(-4.0f, 0.0f, -6.0f), 11.0f};
const Ball kSmall{vec3(6.0f, 2.0f, 12.0f), 4.0f};
const vec3 kLightDirection = glm::normalize(vec3(-0.45f, -0.1f, -1.0f));  // travel direction

Scene shadowed_ball(int image_size, float intensity = 1.0f) {
  const int n = 48;
  Scene scene = procedural_scene("spheres", ivec3(n), image_size);
  auto volume = std::make_shared<Volume>(ivec3(n), VoxelType::Float32);
  float* v = volume->frame_as<float>(0);
  const float c = 0.5f * float(n - 1);
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const vec3 p = vec3(x, y, z) - c;
        *v++ = glm::max(antialiased_solid(glm::length(p - kBig.centre) - kBig.radius),
                        antialiased_solid(glm::length(p - kSmall.centre) - kSmall.radius));
      }
  scene.set_volume(volume);
  scene.set_transfer_function(testing::step_tf(0.5f, vec3(0.9f), 1.0f));
  Light light = testing::directional_light(kLightDirection);
  light.intensity = intensity;
  scene.set_lights({light});
  Material m;
  m.ambient = 0.2f;
  scene.set_material(m);
  scene.set_camera(Camera::framing(Box3{vec3(-16.0f), vec3(16.0f)}, vec3(0.2f, -1.0f, 0.7f)));
  return scene;
}

std::optional<float> hit(const Ball& b, const Ray& ray) {
  const vec3 oc = ray.origin - b.centre;
  const float half_b = glm::dot(oc, ray.direction);
  const float disc = half_b * half_b - (glm::dot(oc, oc) - b.radius * b.radius);
  if (disc < 0.0f) return std::nullopt;
  return -half_b - std::sqrt(disc);
}

// Pixels that see the big ball's surface facing the light (cosine > 0.3),
// whose light ray passes the small ball's centre at a distance in [lo, hi):
// the mean light share, (image - ambient) / (unshadowed - ambient) in green.
struct Share {
  double mean = 0.0;
  int pixels = 0;
};
Share light_share(const Scene& scene, const Image& image, const Image& unshadowed, const Image& ambient, float lo,
                  float hi) {
  const CameraView cam = scene.camera().view();
  const vec3 to_light = -kLightDirection;
  Share s;
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      const Ray ray = cam.pixel_ray(float(x) + 0.5f, float(y) + 0.5f, image.width(), image.height());
      const std::optional<float> t = hit(kBig, ray);
      const std::optional<float> t_small = hit(kSmall, ray);
      if (!t || (t_small && *t_small < *t)) continue;
      const vec3 p = ray.origin + *t * ray.direction;
      if (glm::dot(glm::normalize(p - kBig.centre), to_light) < 0.3f) continue;
      const vec3 to_centre = kSmall.centre - p;
      const float miss = glm::dot(to_centre, to_light) > 0.0f ? glm::length(glm::cross(to_centre, to_light)) : 1e9f;
      const double full = double(unshadowed.at(x, y).g - ambient.at(x, y).g);
      if (miss < lo || miss >= hi || full < 0.05) continue;
      s.mean += double(image.at(x, y).g - ambient.at(x, y).g) / full;
      ++s.pixels;
    }
  }
  s.mean /= std::max(1, s.pixels);
  return s;
}

ParameterSettings dvr(const char* shadows, double light_size_deg) {
  return {{"mode", std::string("dvr")}, {"shadows", std::string(shadows)}, {"iso_value", 0.5},
          {"ambient_occlusion", false}, {"light_size_deg", light_size_deg}};
}

// The small ball's shadow on the big one: dark inside the geometric umbra,
// none well outside it; a wider light reaches further out.
TEST(OcclusionMapDvr, ShadowsFallWhereTheGeometryPutsThem) {
  const Scene scene = shadowed_ball(128);
  const Image none = render_with(scene, "occlusion-map", dvr("none", 0.0));
  const Image ambient = render_with(shadowed_ball(128, 0.0f), "occlusion-map", dvr("none", 0.0));
  const float r = kSmall.radius;
  double rim_small = 0.0;
  for (const double size : {1.0, 16.0}) {
    const Image soft = render_with(scene, "occlusion-map", dvr("soft", size));
    const Share umbra = light_share(scene, soft, none, ambient, 0.0f, r - 1.5f);
    const Share rim = light_share(scene, soft, none, ambient, r, r + 3.0f);
    const Share lit = light_share(scene, soft, none, ambient, r + 6.0f, 1e9f);
    std::printf("[occlusion-map dvr] light %2.0f deg: light share in the umbra %.4f (%d px), just outside it %.4f "
                "(%d px), lit %.4f (%d px)\n",
                size, umbra.mean, umbra.pixels, rim.mean, rim.pixels, lit.mean, lit.pixels);
    EXPECT_GT(umbra.pixels, 30);
    EXPECT_GT(lit.pixels, 200);
    EXPECT_LT(umbra.mean, 0.04) << size;
    if (size == 1.0) {
      EXPECT_GT(lit.mean, 0.9);
      rim_small = rim.mean;
    } else {
      EXPECT_LT(rim.mean, rim_small - 0.04);
    }
  }
}

// The grids' marches run as SIMD packets where the CPU has them: the same
// image as the scalar march, on every packet width this CPU and build have.
TEST(OcclusionMapDvr, PacketGridsMatchTheScalarMarch) {
  const Scene scene = shadowed_ball(48);
  const SimdMode saved = simd_mode();
  set_simd_mode(SimdMode::Off);
  const Image scalar = render_with(scene, "occlusion-map", dvr("soft", 4.0));
  int widths = 0;
  for (const char* name : {"avx2", "avx512"}) {
    try {
      set_simd_mode(parse_simd_mode(name));
    } catch (const InvalidArgument&) {
      continue;  // not on this CPU or in this build
    }
    const Image packets = render_with(scene, "occlusion-map", dvr("soft", 4.0));
    EXPECT_LE(rmse(packets, scalar), 1e-5) << name;
    ++widths;
  }
  set_simd_mode(saved);
  std::printf("[occlusion-map dvr] packet grids checked at %d widths\n", widths);
}

// Two DVR scenes under a Phong-shaded directional light: the Marschner-Lobb
// field under a semi-transparent step TF, and two balls over a slab under a
// step TF of alpha 0.6.
Material phong_material() {
  Material m;
  m.ambient = 0.3f;
  m.shading = Shading::Phong;
  return m;
}
const Light kSideLight = testing::directional_light(glm::normalize(vec3(-0.3f, 0.6f, -1.0f)));
Scene wave_scene(int image_size) {
  Scene wave = procedural_scene("marschner-lobb", ivec3(41), image_size);
  wave.set_transfer_function(testing::step_tf(0.4f, vec3(0.9f, 0.8f, 0.7f), 0.5f));
  wave.set_camera(Camera::framing(wave.volume().world_box(), vec3(0.5f, -1.0f, 0.6f)));
  wave.set_lights({kSideLight});
  wave.set_material(phong_material());
  return wave;
}
Scene balls_over_slab(int image_size) {
  Scene balls = shadowed_ball(image_size);
  auto volume = std::make_shared<Volume>(ivec3(40), VoxelType::Float32);
  float* v = volume->frame_as<float>(0);
  for (int z = 0; z < 40; ++z)
    for (int y = 0; y < 40; ++y)
      for (int x = 0; x < 40; ++x) {
        const vec3 p = vec3(x, y, z) - 19.5f;
        *v++ = glm::max(glm::max(antialiased_solid(glm::length(p - vec3(-5.0f, 0.0f, 2.0f)) - 8.0f),
                                 antialiased_solid(glm::length(p - vec3(9.0f, 3.0f, -3.0f)) - 4.0f)),
                        antialiased_solid(std::abs(p.z + 12.0f) - 2.0f));
      }
  balls.set_volume(volume);
  balls.set_transfer_function(testing::step_tf(0.3f, vec3(0.9f), 0.6f));
  balls.set_camera(Camera::framing(volume->world_box(), vec3(0.4f, -1.0f, 0.7f)));
  balls.set_lights({kSideLight});
  balls.set_material(phong_material());
  return balls;
}

// DVR samples are lit as packets of the shared loop where the CPU has them
// (ambient occlusion, the shadow grids' lookups, Phong normals): the scalar
// path's image on a smooth, semi-transparent volume that is not two-valued
// (Marschner-Lobb) and on balls over a slab (where a packet mixes samples
// whose AO regions reach occluders with samples whose regions do not), with
// the AO per sample at two combinations and from its grid (whose nodes are
// evaluated as packets too).
TEST(OcclusionMapDvr, PacketSamplesMatchTheScalarPath) {
  const Scene wave = wave_scene(64);
  const Scene balls = balls_over_slab(64);
  const SimdMode saved = simd_mode();
  for (const auto& [name, scene] : {std::pair{"marschner-lobb", wave}, std::pair{"balls-over-slab", balls}}) {
    for (const auto& [combine, ao] : {std::pair{"product", "sample"}, std::pair{"max", "sample"},
                                      std::pair{"product", "grid"}}) {
      const ParameterSettings params{{"mode", std::string("dvr")},
                                     {"iso_value", 0.45},
                                     {"ao_combine", std::string(combine)},
                                     {"dvr_ao", std::string(ao)}};
      set_simd_mode(SimdMode::Off);
      RenderStats scalar_stats;
      const Image scalar = render_with(scene, "occlusion-map", params, &scalar_stats);
      ASSERT_EQ(scalar_stats.simd, SimdTarget::Scalar);
      testing::save_test_image(scalar, std::string("occlusion-map-dvr-packets-") + name + "-" + combine + "-" + ao);
      for (const char* target : {"avx2", "avx512"}) {
        try {
          set_simd_mode(parse_simd_mode(target));
        } catch (const InvalidArgument&) {
          continue;  // not on this CPU or in this build
        }
        RenderStats stats;
        const Image packets = render_with(scene, "occlusion-map", params, &stats);
        EXPECT_EQ(stats.simd, active_simd_target()) << target;  // the samples did run as packets
        const double error = rmse(packets, scalar);
        std::printf("[occlusion-map dvr] %s, %s packets, AO %s per %s: rmse %.2e against scalar\n", name, target,
                    combine, ao, error);
        EXPECT_LE(error, 1e-5) << name << " " << target << " " << combine << " " << ao;
      }
    }
  }
  set_simd_mode(saved);
}

// The grids depend on the data, the iso-value, the lights' placement and size
// and the march's parameters; a TF, camera or AO change keeps them, and iso
// mode frees them.
TEST(OcclusionMapDvr, GridsRebuildForLightsAndIsoValueNotForTfOrCamera) {
  Scene scene = shadowed_ball(16);
  const TechniqueInfo& info = find_technique("occlusion-map");
  ParameterValues params(info.parameters);
  params.set("mode", std::string("dvr"));
  params.set("iso_value", 0.5);
  params.set("dvr_ao", std::string("sample"));  // no AO grid (AmbientGridRebuildsForDataAndAoParametersOnly)
  auto technique = info.create();
  Image image;
  technique->prepare(scene, params);
  technique->render(scene, image);
  EXPECT_EQ(technique->rebuilds(), 2u);  // the pyramid and the light's grid
  // One float per node of a 24^3 grid (resolution 0.5) on top of the map.
  const std::uint64_t with_grid = technique->aux_bytes();

  scene.set_transfer_function(testing::step_tf(0.4f, vec3(0.5f), 1.0f));
  scene.set_camera(Camera::framing(scene.volume().world_box(), vec3(1.0f, 0.2f, 0.3f)));
  params.set("ambient_occlusion", false);
  technique->prepare(scene, params);
  technique->render(scene, image);
  EXPECT_EQ(technique->rebuilds(), 2u);

  Light light = scene.lights()[0];
  light.direction = glm::normalize(vec3(0.3f, 0.2f, -1.0f));
  scene.set_lights({light});
  technique->prepare(scene, params);
  EXPECT_EQ(technique->rebuilds(), 3u);
  params.set("iso_value", 0.6);
  technique->prepare(scene, params);
  EXPECT_EQ(technique->rebuilds(), 4u);
  params.set("light_size_deg", 8.0);
  technique->prepare(scene, params);
  EXPECT_EQ(technique->rebuilds(), 5u);
  technique->render(scene, image);

  params.set("mode", std::string("iso"));
  technique->prepare(scene, params);
  EXPECT_EQ(technique->aux_bytes() + 24u * 24u * 24u * sizeof(float), with_grid);
}

// DVR mode's AO read from its grid (dvr_ao=grid, the default: one node per
// voxel, each evaluated as a sample there would be but with the receiver's
// value one voxel under it, homogeneous nodes filled from their neighbours;
// read trilinearly) against the AO evaluated per sample (the paper), without
// shadows. The grid's error is measured against what the AO changes: the
// per-sample AO image against the image without AO. Measured at 96^2 (rmse,
// grid against per sample / per sample against no AO): balls over a slab
// 6.9e-3 / 0.096 (7.2 %; with the receiver's value half a voxel under each
// node 28 %, with homogeneous nodes left at 1 17 %); the Marschner-Lobb
// field, whose detail is 2-3 voxels wide so that the AO changes within a
// voxel, 4.1e-2 / 0.181 (22 %).
TEST(OcclusionMapDvr, AmbientGridFollowsThePerSampleAmbient) {
  for (const auto& [name, scene, bound] : {std::tuple{"balls-over-slab", balls_over_slab(96), 0.12},
                                           std::tuple{"marschner-lobb", wave_scene(96), 0.33}}) {
    ParameterSettings params{{"mode", std::string("dvr")}, {"iso_value", 0.45}, {"shadows", std::string("none")}};
    const Image grid = render_with(scene, "occlusion-map", params);
    params["dvr_ao"] = std::string("sample");
    const Image sample = render_with(scene, "occlusion-map", params);
    params["ambient_occlusion"] = false;
    const Image none = render_with(scene, "occlusion-map", params);
    const double error = rmse(grid, sample), effect = rmse(sample, none);
    std::printf("[occlusion-map dvr ao grid] %s: rmse grid / per sample %.2e, per sample / no AO %.4f (%.1f %%)\n",
                name, error, effect, 100.0 * error / effect);
    testing::save_test_image(grid, std::string("occlusion-map-dvr-ao-grid-") + name + ".png");
    testing::save_test_image(sample, std::string("occlusion-map-dvr-ao-sample-") + name + ".png");
    EXPECT_GT(effect, 0.05) << name;
    EXPECT_LT(error, bound * effect) << name;
  }
}

// The AO grid depends on the data and the AO's own parameters (ao_offset,
// ao_combine, the pyramid's): the iso-value, the TF, the camera and the
// lights keep it (the AO's query is each sample's own value); per-sample AO
// or no AO frees it. 16-bit, one texel per voxel. The light's soft-shadow
// grid does not depend on the AO's settings.
TEST(OcclusionMapDvr, AmbientGridRebuildsForDataAndAoParametersOnly) {
  Scene scene = shadowed_ball(16);
  const TechniqueInfo& info = find_technique("occlusion-map");
  ParameterValues params(info.parameters);
  params.set("mode", std::string("dvr"));
  params.set("shadows", std::string("none"));
  auto technique = info.create();
  Image image;
  technique->prepare(scene, params);
  technique->render(scene, image);
  EXPECT_EQ(technique->rebuilds(), 2u);  // the pyramid and the AO grid

  params.set("iso_value", 0.6);
  scene.set_transfer_function(testing::step_tf(0.4f, vec3(0.5f), 1.0f));
  scene.set_camera(Camera::framing(scene.volume().world_box(), vec3(1.0f, 0.2f, 0.3f)));
  Light light = scene.lights()[0];
  light.direction = glm::normalize(vec3(0.3f, 0.2f, -1.0f));
  scene.set_lights({light});
  technique->prepare(scene, params);
  technique->render(scene, image);
  EXPECT_EQ(technique->rebuilds(), 2u);

  params.set("ao_offset", 3.0);
  technique->prepare(scene, params);
  EXPECT_EQ(technique->rebuilds(), 3u);
  params.set("ao_combine", std::string("max"));
  technique->prepare(scene, params);
  EXPECT_EQ(technique->rebuilds(), 4u);
  params.set("kernel_size", 3.0);
  technique->prepare(scene, params);
  EXPECT_EQ(technique->rebuilds(), 6u);  // the pyramid, then the grid from it

  const std::uint64_t with_grid = technique->aux_bytes();
  params.set("dvr_ao", std::string("sample"));
  technique->prepare(scene, params);
  EXPECT_EQ(technique->rebuilds(), 6u);
  EXPECT_EQ(technique->aux_bytes() + 48u * 48u * 48u * sizeof(std::uint16_t), with_grid);
  params.set("dvr_ao", std::string("grid"));
  params.set("ambient_occlusion", false);
  technique->prepare(scene, params);
  EXPECT_EQ(technique->rebuilds(), 6u);
  EXPECT_EQ(technique->aux_bytes() + 48u * 48u * 48u * sizeof(std::uint16_t), with_grid);

  // With soft shadows the light's grid is built once: the AO's settings keep it.
  params.set("ambient_occlusion", true);
  params.set("shadows", std::string("soft"));
  technique->prepare(scene, params);
  EXPECT_EQ(technique->rebuilds(), 8u);  // the light's grid and the AO grid
  params.set("dvr_ao", std::string("sample"));
  technique->prepare(scene, params);
  EXPECT_EQ(technique->rebuilds(), 8u);
  params.set("dvr_ao", std::string("grid"));
  technique->prepare(scene, params);
  EXPECT_EQ(technique->rebuilds(), 9u);  // the AO grid only

  // New data: the pyramid, the light's grid and the AO grid.
  scene.set_volume(make_procedural_volume("shell", ivec3(48)));
  technique->prepare(scene, params);
  EXPECT_EQ(technique->rebuilds(), 12u);
}

// Hard shadows are iso-test rays from a surface: mode dvr names the parameter.
TEST(OcclusionMapDvr, HardShadowsNeedIsoMode) {
  const Scene scene = shadowed_ball(8);
  try {
    render_with(scene, "occlusion-map", {{"mode", std::string("dvr")}, {"shadows", std::string("hard")}});
    ADD_FAILURE() << "no error";
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.name(), "shadows") << e.what();
  }
}

}  // namespace
}  // namespace penumbra

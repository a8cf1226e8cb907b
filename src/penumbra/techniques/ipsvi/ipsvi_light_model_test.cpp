// ipsvi's paper light model (light_model.h) against what its equations
// predict: Eq. 3's coloured direct light through a homogeneous slab onto a
// white floor, Eq. 2's blend by the sample's own albedo a(s), the cone-mean
// phase of the scattered part; and the grey default left as it was.
#include "penumbra/base/error.h"
#include "penumbra/scene/material.h"
#include "penumbra/techniques/ipsvi/light_model.h"
#include "penumbra/techniques/ipsvi/sweep_renderer.h"
#include "penumbra/techniques/registry.h"
#include "test_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace penumbra {
namespace {

Image render_light_model(const Scene& scene, IpsviLightModel model, float albedo = 0.0f, float cone_deg = 20.0f) {
  IpsviSettings s;
  s.light_model = model;
  s.albedo = albedo;
  s.cone_angle_deg = cone_deg;
  IpsviRenderer r;
  r.prepare(scene, s);
  Image image;
  r.render(scene, image);
  return image;
}

// A 24 x 24 x 8 slab of colour `color` and extinction sigma per unit,
// lit at 45 degrees; a white floor 30 below it, seen from straight above
// where its light has crossed the whole slab, and nothing else in view.
struct SlabOverFloor {
  Scene scene;
  float path = 0.0f;  // the light's path through the slab
};

SlabOverFloor slab_over_floor(vec3 color, float sigma) {
  SlabOverFloor out;
  out.scene = testing::procedural_scene("slab", ivec3(24, 24, 8), 24);
  out.scene.set_transfer_function(testing::step_tf(0.0f, color, 1.0f - std::exp(-sigma)));
  const Box3 box = out.scene.volume().world_box();
  const vec3 to_light = glm::normalize(vec3(-1.0f, 0.0f, 1.0f));
  out.scene.set_lights({testing::directional_light(-to_light)});
  const float floor_z = box.lower.z - 30.0f;
  out.scene.set_planes({Plane{vec3(0.0f, 0.0f, floor_z), vec3(0.0f, 0.0f, 1.0f), vec3(1.0f)}});
  Material m;
  m.ambient = 0.0f;
  out.scene.set_material(m);
  // The floor point whose light ray crosses the box centre.
  const vec3 spot(box.center().x + (box.center().z - floor_z), box.center().y, floor_z);
  Camera camera;
  camera.eye = spot + vec3(0.0f, 0.0f, 70.0f);
  camera.target = spot;
  camera.up = vec3(0.0f, 1.0f, 0.0f);
  camera.fov_deg = 8.0f;
  out.scene.set_camera(camera);
  out.path = box.extent().z * std::sqrt(2.0f);
  return out;
}

// Eq. 3 through a homogeneous slab of colour c and optical depth tau:
// I = T + (1 - T) c with T = exp(-tau). The floor (white, facing up, no
// ambient) shows cos(45 deg) I. Measured: max |error| 2e-6 over the image.
TEST(IpsviLightModel, ColouredSlabTintsTheFloorAsEquation3Predicts) {
  const vec3 color(1.0f, 0.3f, 0.1f);
  const float sigma = 0.25f;
  const SlabOverFloor s = slab_over_floor(color, sigma);
  const float t = std::exp(-sigma * s.path);
  const vec3 expected = std::sqrt(0.5f) * (vec3(t) + (1.0f - t) * color);
  const Image paper = render_light_model(s.scene, IpsviLightModel::Paper);
  const Image grey = render_light_model(s.scene, IpsviLightModel::Grey);
  testing::save_test_image(paper, "ipsvi-paper-slab-floor.png");
  float error = 0.0f, grey_error = 0.0f;
  for (int y = 0; y < paper.height(); ++y) {
    for (int x = 0; x < paper.width(); ++x) {
      error = std::max(error, max_component(glm::abs(vec3(paper.at(x, y)) - expected)));
      grey_error = std::max(grey_error, max_component(glm::abs(vec3(grey.at(x, y)) - std::sqrt(0.5f) * vec3(t))));
    }
  }
  const vec3 centre(paper.at(12, 12));
  std::printf("slab over floor: T %.4f, expected %.4f %.4f %.4f, paper %.4f %.4f %.4f; max error paper %.2g, "
              "grey %.2g\n",
              t, expected.r, expected.g, expected.b, centre.r, centre.g, centre.b, error, grey_error);
  EXPECT_LT(error, 1e-4f);
  EXPECT_LT(grey_error, 1e-4f) << "the grey model keeps the grey transmittance";
}

// A black medium adds no colour to the light: the paper model's direct light
// is then the grey transmittance, computed through the colour channel, and
// the image is the grey model's (floor shadows and all), to the bit as
// measured; the bound allows for the order of float operations.
TEST(IpsviLightModel, BlackMediumGivesTheGreyImage) {
  Scene scene = testing::with_floor(testing::lit_spheres(40));
  scene.set_transfer_function(testing::step_tf(0.2f, vec3(0.0f), 0.3f));
  const Image grey = render_light_model(scene, IpsviLightModel::Grey);
  const Image paper = render_light_model(scene, IpsviLightModel::Paper);
  float diff = 0.0f;
  for (std::size_t i = 0; i < grey.pixels().size(); ++i) {
    diff = std::max(diff, max_component(glm::abs(grey.pixels()[i] - paper.pixels()[i])));
  }
  std::printf("black medium: max |paper - grey| %.3g\n", diff);
  EXPECT_LT(diff, 1e-6f);
}

// Eq. 2 with a(s) = albedo x the sample's scattering albedo (material.albedo
// x TF colour, per channel). With a cone of 0 degrees and an isotropic phase
// I_ms is the grey transmittance (the grey model at albedo 1), and the
// image, linear in V, is per channel
//   (1 - a) (paper model at albedo 0) + a (grey model at albedo 1)
// up to the trailing cache, which is on only without the scattered part.
// Measured: max |error| 0.0057 (the image's brightest channel 0.76); with
// a(s) = albedo (the colour left out) 0.091.
TEST(IpsviLightModel, AlbedoIsTheSamplesOwnPerChannel) {
  Scene scene = testing::procedural_scene("slab", ivec3(24, 24, 12), 24);
  const vec3 color(1.0f, 0.5f, 0.2f);
  scene.set_transfer_function(testing::step_tf(0.0f, color, 0.12f));
  scene.set_lights({testing::directional_light(vec3(0.3f, 0.5f, -1.0f))});
  Material m;
  m.ambient = 0.0f;
  m.albedo = 0.8f;
  scene.set_material(m);
  const vec3 a = m.albedo * color;
  const Image single = render_light_model(scene, IpsviLightModel::Paper, 0.0f, 0.0f);
  const Image multiple = render_light_model(scene, IpsviLightModel::Grey, 1.0f, 0.0f);
  const Image blended = render_light_model(scene, IpsviLightModel::Paper, 1.0f, 0.0f);
  float error = 0.0f, brightest = 0.0f, spread = 0.0f;
  for (std::size_t i = 0; i < blended.pixels().size(); ++i) {
    const vec3 s(single.pixels()[i]), ms(multiple.pixels()[i]);
    const vec3 expected = (vec3(1.0f) - a) * s + a * ms;
    error = std::max(error, max_component(glm::abs(vec3(blended.pixels()[i]) - expected)));
    brightest = std::max(brightest, max_component(s));
    spread = std::max(spread, max_component(glm::abs(s - ms)));
  }
  std::printf("a(s) per channel: max error %.4f (brightest %.3f, |I_ss - I_ms| up to %.3f)\n", error, brightest,
              spread);
  EXPECT_GT(spread, 0.05f) << "the test needs the two parts to differ";
  EXPECT_LT(error, 0.015f);
}

// The scattered part arrives from the whole cone: its phase is the cone's
// mean of p. A white medium of material albedo 1 has a(s) = 1, so V is
// I_ms times that ratio, and I_ms is what the grey model at albedo 1 uses.
// With an orthographic camera and a directional light the angle is the same
// at every pixel, so the image is the grey one times ConePhase::at(cos).
TEST(IpsviLightModel, ScatteredPartTakesTheConeMeanPhase) {
  Scene scene = testing::procedural_scene("slab", ivec3(24, 24, 12), 24);
  scene.set_transfer_function(testing::step_tf(0.0f, vec3(1.0f), 0.1f));
  const Light light = testing::directional_light(vec3(-0.25f, -1.0f, 0.0f));  // toward the camera: forward scattering
  scene.set_lights({light});
  Camera camera = testing::orthographic_camera(vec3(0.0f, -100.0f, 10.0f), 40.0f, vec3(0.0f, 0.0f, 1.0f));
  scene.set_camera(camera);
  Material m;
  m.ambient = 0.0f;
  m.phase_g = 0.7f;
  scene.set_material(m);
  const float cone = 30.0f;
  const Image grey = render_light_model(scene, IpsviLightModel::Grey, 1.0f, cone);
  const Image paper = render_light_model(scene, IpsviLightModel::Paper, 1.0f, cone);
  const vec3 view_dir = glm::normalize(camera.target - camera.eye);
  const float ratio = make_cone_phase(m.phase_g, cone).at(glm::dot(-light.direction, view_dir));
  float error = 0.0f;
  int lit = 0;
  for (std::size_t i = 0; i < grey.pixels().size(); ++i) {
    const vec3 g(grey.pixels()[i]);
    if (max_component(g) < 1e-3f) continue;
    ++lit;
    error = std::max(error, max_component(glm::abs(vec3(paper.pixels()[i]) - ratio * g)) / max_component(g));
  }
  std::printf("cone-mean phase: ratio %.4f, %d pixels, max relative error %.2g\n", ratio, lit, error);
  EXPECT_GT(lit, 100);
  EXPECT_GT(std::abs(ratio - 1.0f), 0.1f) << "the test needs a ratio away from 1";
  EXPECT_LT(error, 1e-4f);
}

// The table against the closed form along the axis (view direction at the
// cone's axis or opposite it), where the mean over the cone is
// (1 - g^2) / g (d(1)^-1/2 - d(cos theta)^-1/2) / (1 - cos theta) with
// d(u) = 1 + g^2 -+ 2 g u; against a brute-force mean over a fine grid of
// the cone's directions elsewhere; and 1 without a cone or for isotropic
// scattering.
TEST(IpsviLightModel, ConePhaseMatchesTheClosedFormAndBruteForce) {
  for (const float g : {0.6f, -0.3f, 0.9f}) {
    for (const float cone : {10.0f, 30.0f, 60.0f}) {
      const ConePhase table = make_cone_phase(g, cone);
      const double c = std::cos(double(glm::radians(cone)));
      for (const double mu : {1.0, -1.0}) {
        const double gg = double(g) * mu;
        auto inverse_root = [&](double u) { return 1.0 / std::sqrt(1.0 + gg * gg - 2.0 * gg * u); };
        const double mean = (1.0 - gg * gg) / gg * (inverse_root(1.0) - inverse_root(c)) / (1.0 - c);
        const double expected = mean / double(phase_hg_4pi(g, float(mu)));
        EXPECT_NEAR(table.at(float(mu)), expected, 2e-3 * expected) << "g " << g << ", cone " << cone << ", mu " << mu;
      }
    }
  }
  for (const float g : {0.5f, -0.4f}) {
    const float cone = 25.0f;
    const ConePhase table = make_cone_phase(g, cone);
    const double c = std::cos(double(glm::radians(cone)));
    for (int i = 8; i < ConePhase::kEntries; i += 16) {  // entries away from the axis
      const double mu = -1.0 + 2.0 * i / double(ConePhase::kEntries);
      const dvec3 view(std::sqrt(1.0 - mu * mu), 0.0, mu);
      double sum = 0.0;
      const int rings = 600, sectors = 600;
      for (int r = 0; r < rings; ++r) {
        const double u = c + (1.0 - c) * (r + 0.5) / rings;  // uniform in solid angle
        for (int k = 0; k < sectors; ++k) {
          const double phi = 2.0 * kPi * (k + 0.5) / sectors;
          const dvec3 w(std::sqrt(1.0 - u * u) * std::cos(phi), std::sqrt(1.0 - u * u) * std::sin(phi), u);
          sum += double(phase_hg_4pi(g, float(glm::dot(w, view))));
        }
      }
      const double expected = sum / (rings * sectors) / double(phase_hg_4pi(g, float(mu)));
      EXPECT_NEAR(table.ratio[i], expected, 1e-3 * expected) << "g " << g << ", mu " << mu;
    }
  }
  EXPECT_EQ(make_cone_phase(0.0f, 30.0f).at(0.3f), 1.0f);
  EXPECT_EQ(make_cone_phase(0.7f, 0.0f).at(0.3f), 1.0f);
}

TEST(IpsviLightModel, UnknownModelNamesTheParameter) {
  ParameterValues params(find_technique("ipsvi").parameters);
  EXPECT_EQ(params.choice("light_model"), "grey");
  try {
    params.set("light_model", std::string("chromatic"));
    ADD_FAILURE() << "light_model accepted chromatic";
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.name(), "light_model");
  }
}

}  // namespace
}  // namespace penumbra

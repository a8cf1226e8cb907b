// convolution's per-pixel jitter within slabs (issue 23): the `jitter`
// parameter and the scene's render.jitter, the moire it removes from a cut
// face of fine detail, and the exact integration it keeps.
#include "penumbra/scene/mesh_shapes.h"
#include "penumbra/techniques/registry.h"
#include "penumbra/volume/volume.h"
#include "test_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <vector>

namespace penumbra {
namespace {

using testing::procedural_scene;
using testing::render_with;

// The Marschner-Lobb field (detail a few voxels across) in a 64^3 box with a
// clip plane cutting it, seen obliquely by an orthographic camera and lit by
// a directional light: the cut face is where fixed slab planes alias the
// detail into bands (scripts/convolution-rings.py measures the same on the
// engine CT).
Scene cut_detail_scene(int image) {
  Scene scene = procedural_scene("marschner-lobb", ivec3(64), image);
  scene.set_transfer_function(TransferFunction(
      {{0.0f, vec3(0.2f, 0.3f, 0.8f), 0.0f}, {0.5f, vec3(0.8f), 0.1f}, {1.0f, vec3(1.0f, 0.7f, 0.4f), 0.6f}}));
  scene.set_camera(testing::orthographic_camera(vec3(120.0f, -60.0f, 50.0f), 80.0f, vec3(0.0f, 0.0f, 1.0f)));
  scene.set_lights({testing::directional_light(glm::normalize(vec3(-0.3f, 0.8f, -0.5f)))});
  Material m;
  m.shading = Shading::Phase;
  m.ambient = 0.15f;
  scene.set_material(m);
  scene.set_clip_planes({vec4(-1.0f, 0.0f, 0.0f, 5.0f)});
  return scene;
}

// Per-pixel grey error of `image` against `reference`, box-filtered over 5x5
// pixels, as an RMS: the structured part of the error (bands, moire), in
// which the noise that jitter trades them for averages out.
double structured_error(const Image& image, const Image& reference) {
  const int w = image.width(), h = image.height();
  std::vector<double> err(std::size_t(w) * std::size_t(h));
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const vec4 d = image.at(x, y) - reference.at(x, y);
      err[std::size_t(x + w * y)] = (d.x + d.y + d.z) / 3.0;
    }
  }
  double sum = 0.0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      double box = 0.0;
      for (int dy = -2; dy <= 2; ++dy) {
        for (int dx = -2; dx <= 2; ++dx) {
          const int xx = glm::clamp(x + dx, 0, w - 1), yy = glm::clamp(y + dy, 0, h - 1);
          box += err[std::size_t(xx + w * yy)];
        }
      }
      sum += (box / 25.0) * (box / 25.0);
    }
  }
  return std::sqrt(sum / double(w * h));
}

// The rectangle [x0, x1) x [y0, y1) of an image.
Image crop(const Image& image, int x0, int y0, int x1, int y1) {
  Image out(x1 - x0, y1 - y0);
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) out.at(x - x0, y - y0) = image.at(x, y);
  }
  return out;
}

// The per-pixel grey error's RMS.
double pixel_rms(const Image& image, const Image& reference) {
  double sum = 0.0;
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      const vec4 d = image.at(x, y) - reference.at(x, y);
      const double grey = (d.x + d.y + d.z) / 3.0;
      sum += grey * grey;
    }
  }
  return std::sqrt(sum / double(image.width() * image.height()));
}

// Jitter trades the bands of fixed slab planes for noise: the structured
// error against a render at an eighth of the slab distance falls. Measured
// (96^2): 18.8e-3 -> 15.3e-3 at e = 2 voxels, 38.2e-3 -> 29.2e-3 at e = 4
// (ratios 0.81, 0.76); the per-pixel error grows a little (the noise).
// Without the jitter (the offset left at 0.5) both ratios are 1.
TEST(ConvolutionJitter, TradesCutFaceBandsForNoise) {
  const Scene scene = cut_detail_scene(96);
  const Image reference = render_with(scene, "convolution", {{"slab_distance", 0.5}, {"jitter", std::string("off")}});
  for (const double e : {2.0, 4.0}) {
    const Image fixed = render_with(scene, "convolution", {{"slab_distance", e}, {"jitter", std::string("off")}});
    const Image jittered = render_with(scene, "convolution", {{"slab_distance", e}, {"jitter", std::string("on")}});
    if (e == 4.0) {
      testing::save_test_image(fixed, "conv_jitter_off.png");
      testing::save_test_image(jittered, "conv_jitter_on.png");
    }
    const double without = structured_error(fixed, reference), with = structured_error(jittered, reference);
    EXPECT_GT(without, 0.01) << "e " << e << ": the fixed slabs must show bands for the test to mean anything";
    EXPECT_LT(with, 0.9 * without) << "e " << e;
  }
}

// A homogeneous mesh sphere (radius 22, sigma about 0.5 per unit) at the
// centre of an orthographic view from +z, 96^2 over 60 units, lit by a
// directional light `tilt` off the view axis (0: along it).
Scene ring_sphere_scene(vec3 light_direction) {
  Scene scene = procedural_scene("empty", ivec3(64), 96);
  scene.set_transfer_function(TransferFunction({{0.0f, vec3(1.0f), 0.0f}, {1.0f, vec3(1.0f), 0.0f}}));
  scene.set_camera(testing::orthographic_camera(vec3(0.0f, 0.0f, 100.0f), 60.0f));
  scene.set_lights({testing::directional_light(glm::normalize(light_direction))});
  Material m;
  m.shading = Shading::Phase;
  m.ambient = 0.1f;
  scene.set_material(m);
  scene.set_meshes({testing::homogeneous_mesh("sphere", 4, 22.0f, vec3(0.9f, 0.8f, 0.7f), 0.4f)});
  return scene;
}

// Ring energy of `image` against `reference` about the image centre: the RMS
// of the grey error's mean over one-pixel annuli, less a 9-annulus moving
// average of that profile (scripts/convolution-rings.py). Rings concentric
// about the centre keep their amplitude; noise averages out over an annulus.
double ring_energy(const Image& image, const Image& reference, double radius) {
  const int w = image.width(), h = image.height();
  const int bins = int(radius) + 1;
  std::vector<double> sum(std::size_t(bins), 0.0), count(std::size_t(bins), 0.0);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const double r = std::hypot(x + 0.5 - 0.5 * w, y + 0.5 - 0.5 * h);
      if (r >= radius) continue;
      const vec4 d = image.at(x, y) - reference.at(x, y);
      sum[std::size_t(r)] += (d.x + d.y + d.z) / 3.0;
      count[std::size_t(r)] += 1.0;
    }
  }
  std::vector<double> profile;
  for (int b = 0; b < bins; ++b) {
    if (count[std::size_t(b)] > 0.0) profile.push_back(sum[std::size_t(b)] / count[std::size_t(b)]);
  }
  const int n = int(profile.size());
  double energy = 0.0;
  for (int i = 0; i < n; ++i) {
    double smooth = 0.0;
    for (int k = -4; k <= 4; ++k) smooth += profile[std::size_t(glm::clamp(i + k, 0, n - 1))] / 9.0;
    energy += (profile[std::size_t(i)] - smooth) * (profile[std::size_t(i)] - smooth);
  }
  return std::sqrt(energy / n);
}

// The slab rings on a mesh sphere (issue 23): the light's paths cross the
// slabs slanted, and where the surface is tilted to them a path enters or
// leaves the mesh at another depth than the pixel's column does
// (slanted_paths.h). Lit along the view axis there are none; with a tilted
// light they were 11.7e-3 at e = 2 and 3.45e-3 at e = 1 (96^2, against e =
// 0.25) while light was attenuated down each column. Taken along the paths
// (the slab's attenuation, each sample's light to its part's front and back,
// and read where the ray through the part's middle crossed the slab's plane):
// 4.07e-3 and 2.04e-3; without the read off the plane 5.1e-3 at e = 2.
// Jitter leaves them as they are, and they still shrink with e.
TEST(ConvolutionJitter, MeshSphereRingsShrinkAlongSlantedLightPaths) {
  const double radius = 0.98 * 22.0 / 60.0 * 96.0;
  const Scene tilted = ring_sphere_scene(vec3(0.5f, 0.4f, -0.77f)), along = ring_sphere_scene(vec3(0.0f, 0.0f, -1.0f));
  const ParameterSettings fine_slabs{{"slab_distance", 0.25}, {"jitter", std::string("off")}};
  const Image tilted_reference = render_with(tilted, "convolution", fine_slabs);
  const Image along_reference = render_with(along, "convolution", fine_slabs);
  const auto rings = [&](const Scene& scene, const Image& reference, double e, const char* jitter) {
    const Image image = render_with(scene, "convolution", {{"slab_distance", e}, {"jitter", std::string(jitter)}});
    return ring_energy(image, reference, radius);
  };
  const double coarse = rings(tilted, tilted_reference, 2.0, "off"), fine = rings(tilted, tilted_reference, 1.0, "off");
  const double jittered = rings(tilted, tilted_reference, 2.0, "on");
  const double axial = rings(along, along_reference, 2.0, "off");
  std::printf("mesh sphere ring energy: tilted e 2 %.2e, e 1 %.2e, jittered %.2e; along the axis %.2e\n", coarse, fine,
              jittered, axial);
  EXPECT_LT(axial, 0.1 * coarse);
  EXPECT_LT(fine, 0.7 * coarse);
  EXPECT_NEAR(jittered, coarse, 0.2 * coarse);
  EXPECT_LT(coarse, 1.2 * 4.07e-3);
  EXPECT_LT(fine, 1.2 * 2.04e-3);
}

// A light far off the view axis drifts several voxels sideways per slab at
// the render step, and the rings grow with the drift: the automatic slab
// distance keeps the drift within a voxel (slab_renderer.h). Against exact
// shadow rays on the homogeneous sphere lit 72 degrees off the view axis
// (tan 3.1; e = 0.33 instead of 1): ring energy 0.71e-3 against 3.86e-3 at
// the step, mean dE 0.112 against 0.431.
TEST(ConvolutionJitter, GrazingLightRingsShrinkWithTheDriftBound) {
  const double radius = 0.98 * 22.0 / 60.0 * 96.0;
  const Scene grazing = ring_sphere_scene(vec3(0.95f, 0.0f, -0.31f));
  const Image rays = render_with(grazing, "shadow-rays", {{"shadow_cache", false}});
  const ParameterSettings off{{"jitter", std::string("off")}};
  ParameterSettings at_step = off;
  at_step["slab_distance"] = 1.0;  // the render step, a voxel
  const Image automatic = render_with(grazing, "convolution", off), stepped = render_with(grazing, "convolution", at_step);
  const double rings_auto = ring_energy(automatic, rays, radius), rings_step = ring_energy(stepped, rays, radius);
  const double de_auto = testing::mean_de(automatic, rays), de_step = testing::mean_de(stepped, rays);
  std::printf("grazing light against shadow-rays: automatic e rings %.2e, mean dE %.3f; e = step rings %.2e, mean dE %.3f\n",
              rings_auto, de_auto, rings_step, de_step);
  EXPECT_LT(rings_auto, 1.3 * 0.71e-3);
  EXPECT_LT(de_auto, 1.3 * 0.112);
  EXPECT_LT(rings_auto, 0.5 * rings_step);
  EXPECT_LT(de_auto, 0.5 * de_step);
}

// The head CT's thin shell (the head rest) over the floor, lit from above:
// its long floor shadow against exact shadow rays, in the rectangle where it
// lies (256^2). Carried texels that cross the shell sample it on their own
// rays; reading the four pixel columns' transmittances instead (bilinear
// weights that cycle as the texels drift past the columns) printed a moire
// into the shadow: structured error 2.72e-2 against 1.13e-2 now, per-pixel
// RMS 5.36e-2 against 2.35e-2 (docs/convolution.md, "Texels that sample the
// volume"). Both bounds fail with the columns' transmittances.
TEST(ConvolutionCarried, ThinShellShadowHasNoMoire) {
  const Scene scene = testing::repository_scene("scenes/head-directional.json", 256);
  const Image rays = render_with(scene, "shadow-rays", {{"shadow_cache", false}});
  const Image conv = render_with(scene, "convolution");
  testing::save_test_image(conv, "convolution-head-shell-shadow.png");
  const Image conv_crop = crop(conv, 0, 150, 80, 200), rays_crop = crop(rays, 0, 150, 80, 200);
  const double structured = structured_error(conv_crop, rays_crop), rms = pixel_rms(conv_crop, rays_crop);
  std::printf("head shell's floor shadow against shadow-rays: structured error %.2e, RMS %.2e\n", structured, rms);
  EXPECT_LT(structured, 1.4 * 1.13e-2);
  EXPECT_LT(rms, 1.4 * 2.35e-2);
}

// `jitter=scene` (the default) follows the scene's render.jitter; the
// explicit values override it.
TEST(ConvolutionJitter, FollowsTheSceneUnlessSet) {
  Scene scene = cut_detail_scene(32);
  const ParameterSettings coarse{{"slab_distance", 3.0}};
  const Image plain = render_with(scene, "convolution", coarse);
  ParameterSettings on = coarse, off = coarse;
  on["jitter"] = std::string("on");
  off["jitter"] = std::string("off");
  const Image forced_on = render_with(scene, "convolution", on);
  EXPECT_GT(testing::mean_de(plain, forced_on), 0.05);
  RenderSettings render = scene.render();
  render.jitter = true;
  scene.set_render(render);
  EXPECT_EQ(testing::mean_de(render_with(scene, "convolution", coarse), forced_on), 0.0);
  EXPECT_EQ(testing::mean_de(render_with(scene, "convolution", off), plain), 0.0);
}

}  // namespace
}  // namespace penumbra

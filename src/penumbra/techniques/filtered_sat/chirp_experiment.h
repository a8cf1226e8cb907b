#pragma once
// The chirp experiment of Ament et al. 2014, Fig. 4, shared by the test and
// the figure in docs/: the `chirp` occluder (a layer whose opacity is a chirp
// along x) over a white floor, a directional light straight down, and an
// orthographic camera straight down whose pixel row across the middle of the
// floor runs along the chirp axis, one pixel per voxel. The occluder is
// invisible to the camera (the render TF is transparent, the shadow TF holds
// its opacity), so a floor pixel is exactly T = exp(-tau) of its shadow ray
// (ambient 0, unit light, white floor at normal incidence). Test-only code.
#include "penumbra/analysis/luminance_profile.h"
#include "penumbra/render/parameters.h"
#include "penumbra/techniques/registry.h"
#include "test_scene.h"

#include <cmath>
#include <vector>

namespace penumbra::testing {

// `size`: the chirp volume (its x extent sets the frequencies: 1 to
// size.x / 8 cycles over the box); the image is size.x - 1 pixels wide.
inline Scene chirp_scene(ivec3 size, int image_height) {
  Scene scene = procedural_scene("chirp", size, image_height);
  scene.set_transfer_function(step_tf(0.0f, vec3(1.0f), 0.0f));
  TransferFunction shadow({{0.0f, vec3(1.0f), 0.0f}, {1.0f, vec3(1.0f), 0.35f}});
  shadow.set_range(vec2(0.0f, 1.0f));
  scene.set_shadow_transfer_function(shadow);
  Light light;
  light.direction = vec3(0.0f, 0.0f, -1.0f);
  scene.set_lights({light});
  Material m;
  m.ambient = 0.0f;
  scene.set_material(m);
  const Box3 box = scene.volume().world_box();
  scene.set_planes({Plane{vec3(0.0f, 0.0f, box.lower.z - 4.0f), vec3(0.0f, 0.0f, 1.0f), vec3(1.0f)}});
  const int width = size.x - 1;
  Camera camera;
  camera.eye = vec3(0.0f, 0.0f, box.upper.z + 50.0f);
  camera.target = vec3(0.0f, 0.0f, box.lower.z);
  camera.up = vec3(0.0f, 1.0f, 0.0f);
  camera.projection = Projection::Orthographic;
  camera.ortho_height = box.extent().x * float(image_height) / float(width);
  scene.set_camera(camera);
  RenderSettings r = scene.render();
  r.width = width;
  r.height = image_height;
  scene.set_render(r);
  return scene;
}

// The optical depth of the floor's shadow along the middle row.
inline std::vector<float> shadow_depth_profile(const Image& floor) {
  std::vector<float> tau = row_luminance(floor, floor.height() / 2);
  for (float& t : tau) t = -std::log(std::max(t, 1e-6f));
  return tau;
}

// Amplitude spectrum of a profile after removing its mean and applying a Hann
// window (which keeps the box's edges at the ends of the profile from
// leaking into every bin). Bin k is k cycles over the profile.
inline std::vector<float> windowed_spectrum(std::vector<float> profile) {
  double mean = 0.0;
  for (float v : profile) mean += v;
  mean /= double(profile.size());
  const double n = double(profile.size());
  for (std::size_t i = 0; i < profile.size(); ++i) {
    const double hann = 0.5 - 0.5 * std::cos(2.0 * 3.14159265358979 * (double(i) + 0.5) / n);
    profile[i] = float((profile[i] - mean) * hann);
  }
  return amplitude_spectrum(profile);
}

// The filters' transfer functions at f cycles per voxel for a box of width w
// and the Gaussian of the same variance (sigma = w / sqrt 12).
inline double box_response(double f, double w) {
  const double x = 3.14159265358979 * w * f;
  return x == 0.0 ? 1.0 : std::abs(std::sin(x) / x);
}
inline double gaussian_response(double f, double w) {
  const double sigma = w / std::sqrt(12.0);
  return std::exp(-2.0 * 9.8696044010893586 * sigma * sigma * f * f);
}

}  // namespace penumbra::testing

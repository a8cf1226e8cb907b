#include "penumbra_edge.h"

#include "test_scene.h"

#include "penumbra/analysis/image_metrics.h"
#include "penumbra/scene/camera.h"

#include <gtest/gtest.h>
#include "penumbra/volume/volume.h"

#include <cmath>
#include <algorithm>
#include <memory>
#include <optional>
#include <vector>

namespace penumbra::testing {

EdgeScene edge_scene(Light light, float distance, int image_size, float view_width, float light_height) {
  // 48 x 48 x 6 voxels of unit spacing centred at the origin; value 1 in the
  // two middle z layers for x < 24 (the half-plane), 0 elsewhere.
  const ivec3 dims(48, 48, 6);
  auto volume = std::make_shared<Volume>(dims, VoxelType::Float32);
  float* v = volume->frame_as<float>(0);
  for (int z = 0; z < dims.z; ++z) {
    for (int y = 0; y < dims.y; ++y) {
      for (int x = 0; x < dims.x; ++x) v[x + dims.x * (y + dims.y * z)] = (x < 24 && (z == 2 || z == 3)) ? 1.0f : 0.0f;
    }
  }
  volume->center_at_origin();
  EdgeScene e;
  // Between voxels 23 and 24, and the mid-plane between layers 2 and 3.
  const vec3 mid = volume->origin() + vec3(23.5f, 0.0f, 2.5f) * volume->spacing();
  e.edge_x = mid.x;
  e.distance = distance;
  e.pixel_size = view_width / float(image_size);
  Scene& s = e.scene;
  s.set_volume(volume);
  s.set_transfer_function(TransferFunction({{0.0f, vec3(0.0f), 0.0f}, {1.0f, vec3(0.0f), 0.0f}}));
  TransferFunction shadow({{0.0f, vec3(0.0f), 0.0f}, {1.0f, vec3(0.0f), 0.999f}});
  shadow.set_range(vec2(0.0f, 1.0f));
  s.set_shadow_transfer_function(shadow);
  TransferFunction tf = s.transfer_function();
  tf.set_range(vec2(0.0f, 1.0f));
  s.set_transfer_function(tf);
  Material m;
  m.ambient = 0.0f;
  s.set_material(m);
  const float floor_z = mid.z - distance;
  s.set_planes({Plane{vec3(0.0f, 0.0f, floor_z), vec3(0.0f, 0.0f, 1.0f), vec3(1.0f)}});
  light.direction = vec3(0.0f, 0.0f, -1.0f);
  if (!light.at_infinity()) light.position = vec3(e.edge_x, 0.0f, mid.z + light_height);
  s.set_lights({light});
  Camera camera;
  camera.eye = vec3(e.edge_x, 0.0f, 100.0f);
  camera.target = vec3(e.edge_x, 0.0f, floor_z);
  camera.up = vec3(0.0f, 1.0f, 0.0f);
  camera.projection = Projection::Orthographic;
  camera.ortho_height = view_width;
  s.set_camera(camera);
  RenderSettings r = s.render();
  r.width = r.height = image_size;
  s.set_render(r);
  return e;
}

Image unshadowed_floor(const EdgeScene& edge) {
  return render_with(edge.scene, "shadow-rays", {{"shadow_density_scale", 0.0}});
}

float penumbra_width_10_90(const EdgeScene& edge, const Image& image, const Image& unshadowed) {
  std::vector<double> profile(std::size_t(image.width()), 0.0);
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      const double lit = unshadowed.at(x, y).r;
      profile[std::size_t(x)] += (lit > 0.0 ? image.at(x, y).r / lit : 0.0) / double(image.height());
    }
  }
  // Orient the profile so that it rises with the index.
  if (profile.front() > profile.back()) std::reverse(profile.begin(), profile.end());
  auto crossing = [&](double level) {
    for (std::size_t i = 1; i < profile.size(); ++i) {
      if (profile[i - 1] < level && profile[i] >= level) {
        return double(i - 1) + (level - profile[i - 1]) / (profile[i] - profile[i - 1]);
      }
    }
    return -1.0e9;  // no crossing: a width no tolerance accepts
  };
  return float((crossing(0.9) - crossing(0.1)) * edge.pixel_size);
}

Image expect_knob_overrides_light(const Scene& scene, const std::string& technique, const ParameterSettings& common,
                                  const std::string& knob, const Light& sized, double matching, const Light& plain,
                                  double plain_default, double other) {
  auto with = [&](const Light& light, std::optional<double> value) {
    Scene s = scene;
    s.set_lights({light});
    ParameterSettings p = common;
    if (value) p[knob] = *value;
    return render_with(s, technique, p);
  };
  const Image derived = with(sized, std::nullopt);
  EXPECT_LT(rmse(derived, with(sized, matching)), 1e-6) << knob << " unset: from the light";
  const Image overridden = with(sized, other);
  EXPECT_GT(rmse(overridden, derived), 1e-3) << knob << " set: the knob, not the light";
  EXPECT_LT(rmse(overridden, with(plain, other)), 1e-6) << knob << " set: the light's size ignored";
  EXPECT_LT(rmse(with(plain, std::nullopt), with(plain, plain_default)), 1e-6) << "a light without a size";
  return overridden;
}

Light distant_light(float angle_deg, LightProfile profile) {
  Light light = as_distant(Light{}, angle_deg);
  light.profile = profile;
  return light;
}

Light as_distant(Light light, float angle_deg) {
  light.type = LightType::Distant;
  light.angle_deg = angle_deg;
  return light;
}

}  // namespace penumbra::testing

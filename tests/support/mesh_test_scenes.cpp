#include "mesh_test_scenes.h"

#include "penumbra/scene/mesh_shapes.h"
#include "test_scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace penumbra::testing {

MeshObject homogeneous_sphere(float radius, vec3 center, float alpha) {
  MeshObject m;
  m.source.builtin = "sphere";
  m.mesh = make_builtin_mesh("sphere", 4);  // 5120 triangles: radial error < 1e-3 R
  m.scale = vec3(radius);
  m.translate = center;
  m.material.detail.type = DetailType::Constant;
  TransferFunction tf({{0.0f, vec3(1.0f), alpha}, {1.0f, vec3(1.0f), alpha}});
  tf.set_unit_length(1.0f);
  m.material.tf = tf;
  m.material.specular = 0.0f;
  return m;
}

Scene mesh_scene(int image, float height, float ambient) {
  Scene scene = procedural_scene("empty", ivec3(32), image);
  Camera cam;
  cam.projection = Projection::Orthographic;
  cam.eye = vec3(0.0f, 0.0f, 100.0f);
  cam.target = vec3(0.0f);
  cam.up = vec3(0.0f, 1.0f, 0.0f);
  cam.ortho_height = height;
  scene.set_camera(cam);
  scene.set_lights({});
  Material m;
  m.ambient = ambient;
  scene.set_material(m);
  return scene;
}

vec2 pixel_world(int x, int y, int image, float height) {
  const float px = height / float(image);
  return vec2((float(x) + 0.5f) * px - 0.5f * height, 0.5f * height - (float(y) + 0.5f) * px);
}

float chord(float radius, vec2 offset) {
  const float r2 = glm::dot(offset, offset);
  return r2 < radius * radius ? 2.0f * std::sqrt(radius * radius - r2) : 0.0f;
}

FloorShadow sphere_floor_shadow(const std::string& technique, const ParameterSettings& params,
                                const std::string& image_name, std::optional<vec3> transport_color) {
  constexpr int kImage = 64;
  constexpr float kHeight = 128.0f;
  constexpr float kRadius = 12.0f;
  Scene scene = mesh_scene(kImage, kHeight, 0.0f);
  MeshObject sphere = homogeneous_sphere(kRadius, vec3(0.0f));
  sphere.material.transport_color = transport_color;
  scene.set_meshes({sphere});
  Light light;
  light.direction = glm::normalize(vec3(1.0f, 0.0f, -1.0f));
  scene.set_lights({light});
  scene.set_planes({Plane{vec3(0.0f, 0.0f, -40.0f), vec3(0.0f, 0.0f, 1.0f), vec3(0.8f)}});
  const Image image = render_with(scene, technique, params);
  save_test_image(image, image_name);
  const float lit = 0.8f * std::sqrt(0.5f);  // colour * cos(45 deg) * L
  const vec3 sigma = -std::log(1.0f - kMeshAlphaPerUnit) * (1.0f - transport_color.value_or(vec3(0.0f)));
  FloorShadow f;
  for (int y = 0; y < kImage; ++y) {
    for (int x = 0; x < kImage; ++x) {
      const vec2 p = pixel_world(x, y, kImage, kHeight);
      if (glm::length(p) < 1.2f * kRadius) continue;  // the sphere itself hides the floor
      const vec3 floor(p, -40.0f);
      const float off_axis = glm::length(glm::cross(floor, light.direction));  // distance of the light ray from the centre
      const float length = chord(kRadius, vec2(off_axis, 0.0f));
      const vec3 pixel(image.at(x, y));
      for (int c = 0; c < 3; ++c) {
        const float expected = lit * std::exp(-sigma[c] * length);
        const float error = std::abs(pixel[c] - expected);
        if (off_axis < 0.5f * kRadius) {
          f.worst_inside = std::max(f.worst_inside, error);
          f.mean_inside += pixel[c] - expected;
        } else if (off_axis > kRadius + 3.0f * kHeight / kImage) {
          f.worst_outside = std::max(f.worst_outside, error);
        }
      }
      if (off_axis < 0.5f * kRadius) {
        f.core += pixel;
        ++f.inside;
      } else if (off_axis > kRadius + 3.0f * kHeight / kImage) {
        ++f.outside;
      }
    }
  }
  f.mean_inside /= 3.0 * std::max(1, f.inside);
  f.core /= float(std::max(1, f.inside));
  std::printf("%s shadow: %d pixels inside, worst %.4f, mean %.4f, core (%.4f, %.4f, %.4f); %d outside, worst %.4f\n",
              technique.c_str(), f.inside, f.worst_inside, f.mean_inside, f.core.r, f.core.g, f.core.b, f.outside,
              f.worst_outside);
  return f;
}

Scene dense_box_scene(bool as_mesh) {
  constexpr float kAlpha = 0.99f;
  Scene scene = procedural_scene("empty", ivec3(32), 48);
  TransferFunction medium({{0.0f, vec3(1.0f), kAlpha}, {1.0f, vec3(1.0f), kAlpha}});
  medium.set_unit_length(1.0f);
  TransferFunction clear({{0.0f, vec3(1.0f), 0.0f}, {1.0f, vec3(1.0f), 0.0f}});
  clear.set_unit_length(1.0f);
  scene.set_transfer_function(as_mesh ? clear : medium);
  if (as_mesh) {
    MeshObject m;
    m.source.builtin = "box";
    m.mesh = make_builtin_mesh("box", 1);
    m.scale = vec3(15.5f);
    m.material.detail.type = DetailType::Constant;
    m.material.tf = medium;
    m.material.specular = 0.0f;
    scene.set_meshes({m});
  }
  Camera cam;
  cam.projection = Projection::Orthographic;
  cam.eye = 100.0f * glm::normalize(vec3(0.45f, 0.35f, 1.0f));
  cam.target = vec3(0.0f);
  cam.up = vec3(0.0f, 1.0f, 0.0f);
  cam.ortho_height = 64.0f;
  scene.set_camera(cam);
  Light light;
  light.direction = glm::normalize(vec3(-0.3f, 0.2f, -1.0f));
  scene.set_lights({light});
  Material mat;
  mat.ambient = 0.0f;
  scene.set_material(mat);
  return scene;
}

BoxComparison compare_box(const Image& mesh, const Image& volume) {
  BoxComparison c;
  double sm = 0.0, sv = 0.0, sd = 0.0;
  int n = 0;
  for (int y = 2; y < mesh.height() - 2; ++y) {
    for (int x = 2; x < mesh.width() - 2; ++x) {
      bool inside = true;
      for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx) inside = inside && volume.at(x + dx, y + dy).a > 0.99f;
      if (!inside) continue;
      const float m = mesh.at(x, y).r, v = volume.at(x, y).r;
      sm += m;
      sv += v;
      sd += double(m - v) * double(m - v);
      ++n;
    }
  }
  EXPECT_GT(n, 400);
  c.mean_mesh = float(sm / n);
  c.mean_volume = float(sv / n);
  c.rms_difference = float(std::sqrt(sd / n));
  return c;
}

}  // namespace penumbra::testing

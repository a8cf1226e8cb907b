#include "test_scene.h"

#include "penumbra/analysis/image_metrics.h"
#include "penumbra/io/image_io.h"
#include "penumbra/io/scene_json.h"
#include "penumbra/render/parameters.h"
#include "penumbra/scene/mesh_shapes.h"
#include "penumbra/techniques/registry.h"

#include <cstdlib>
#include <filesystem>

namespace penumbra::testing {

Scene procedural_scene(const std::string& builtin, ivec3 size, int image_size) {
  Scene scene;
  scene.set_volume(make_procedural_volume(builtin, size));
  TransferFunction tf;
  tf.set_range(vec2(0.0f, 1.0f));
  scene.set_transfer_function(tf);
  scene.set_camera(Camera::framing(scene.volume().world_box(), vec3(0.0f, -1.0f, 0.0f)));
  RenderSettings r;
  r.width = image_size;
  r.height = image_size;
  scene.set_render(r);
  return scene;
}

std::filesystem::path source_dir() {
  // A bundled test binary (scripts/gpu-bundle.sh) runs away from its checkout.
  if (const char* dir = std::getenv("PENUMBRA_TEST_SOURCE_DIR")) return dir;
  return PENUMBRA_SOURCE_DIR;
}

std::filesystem::path shared_data_dir() {
  if (const char* dir = std::getenv("PENUMBRA_TEST_SHARED_DATA_DIR")) return dir;
  return PENUMBRA_SHARED_DATA_DIR;
}

Scene repository_scene(const std::string& relative_path, int image_size) {
  Scene scene = load_scene(source_dir() / relative_path);
  RenderSettings r = scene.render();
  r.width = r.height = image_size;
  scene.set_render(r);
  return scene;
}

Light directional_light(vec3 direction) {
  Light l;
  l.direction = glm::normalize(direction);
  return l;
}

Light point_light(vec3 position) {
  Light l;
  l.type = LightType::Point;
  l.position = position;
  return l;
}

Scene lit_spheres(int image_size) {
  Scene scene = procedural_scene("spheres", ivec3(48), image_size);
  TransferFunction tf({{0.0f, vec3(1.0f, 0.6f, 0.3f), 0.0f},
                       {0.3f, vec3(1.0f, 0.6f, 0.3f), 0.2f},
                       {1.0f, vec3(0.9f, 0.9f, 1.0f), 0.8f}});
  tf.set_range(vec2(0.0f, 1.0f));
  scene.set_transfer_function(tf);
  Light light;
  light.direction = glm::normalize(vec3(0.5f, 0.7f, -1.0f));
  scene.set_lights({light});
  Material m;
  m.ambient = 0.05f;
  scene.set_material(m);
  return scene;
}

Scene with_floor(Scene scene) {
  const float z = scene.volume().world_box().lower.z - 8.0f;
  scene.set_planes({Plane{vec3(0.0f, 0.0f, z), vec3(0.0f, 0.0f, 1.0f), vec3(0.8f)}});
  return scene;
}

void save_test_image(const Image& image, const std::string& name) {
  if (const char* dir = std::getenv("PENUMBRA_TEST_IMAGES")) write_png(std::string(dir) + "/" + name, image);
}

TransferFunction step_tf(float lo, vec3 color, float alpha) {
  std::vector<TransferFunctionPoint> points;
  if (lo > 0.0f) {
    points.push_back({0.0f, color, 0.0f});
    points.push_back({std::max(0.0f, lo - 1e-4f), color, 0.0f});
  }
  points.push_back({lo, color, alpha});
  points.push_back({1.0f, color, alpha});
  TransferFunction tf(points);
  tf.set_range(vec2(0.0f, 1.0f));
  return tf;
}

Image render_with(const Scene& scene, const std::string& technique, const ParameterSettings& params,
                  RenderStats* stats) {
  const TechniqueInfo& info = find_technique(technique);
  ParameterValues values(info.parameters);
  values.apply(params, true);
  auto t = info.create();
  t->prepare(scene, values);
  Image image;
  t->render(scene, image, stats);
  return image;
}

MeshObject homogeneous_mesh(const std::string& builtin, int resolution, float scale, vec3 color, float alpha) {
  MeshObject m;
  m.source.builtin = builtin;
  m.source.resolution = resolution;
  m.mesh = make_builtin_mesh(builtin, resolution);
  m.scale = vec3(scale);
  m.material.detail.type = DetailType::Constant;
  TransferFunction medium({{0.0f, color, alpha}, {1.0f, color, alpha}});
  medium.set_unit_length(1.0f);
  m.material.tf = medium;
  m.material.specular = 0.0f;
  return m;
}

Camera orthographic_camera(vec3 eye, float height, vec3 up) {
  Camera cam;
  cam.projection = Projection::Orthographic;
  cam.eye = eye;
  cam.target = vec3(0.0f);
  cam.up = up;
  cam.ortho_height = height;
  return cam;
}

vec3 mean_rgb(const Image& image, int x0, int y0, int x1, int y1) {
  vec3 sum(0.0f);
  int n = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      sum += vec3(image.at(x, y));
      ++n;
    }
  return n ? sum / float(n) : sum;
}

double mean_de(const Image& a, const Image& b) { return delta_e_stats(a, b).mean; }

float antialiased_solid(float signed_distance) { return glm::clamp(0.5f - signed_distance, 0.0f, 1.0f); }

}  // namespace penumbra::testing

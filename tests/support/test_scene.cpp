#include "test_scene.h"

#include "penumbra/render/parameters.h"
#include "penumbra/techniques/registry.h"

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

Image render_with(const Scene& scene, const std::string& technique, const ParameterSettings& params) {
  const TechniqueInfo& info = find_technique(technique);
  ParameterValues values(info.parameters);
  values.apply(params, true);
  auto t = info.create();
  t->prepare(scene, values);
  Image image;
  t->render(scene, image);
  return image;
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

}  // namespace penumbra::testing

#pragma once
// Scenes shared by filtered-sat's technique tests: the spheres data set
// under a directional light, and with a point light beside it.
#include "penumbra/scene/scene.h"
#include "test_scene.h"

namespace penumbra::testing {

inline Scene sat_spheres(vec3 direction = vec3(0.4f, 0.6f, -1.0f)) {
  Scene scene = procedural_scene("spheres", ivec3(40), 40);
  TransferFunction tf({{0.0f, vec3(1.0f, 0.7f, 0.4f), 0.0f},
                       {0.1f, vec3(1.0f, 0.7f, 0.4f), 0.0f},
                       {0.4f, vec3(1.0f, 0.7f, 0.4f), 0.25f},
                       {1.0f, vec3(0.9f, 0.9f, 1.0f), 0.6f}});
  tf.set_range(vec2(0.0f, 1.0f));
  scene.set_transfer_function(tf);
  Light light;
  light.direction = glm::normalize(direction);
  scene.set_lights({light});
  Material m;
  m.ambient = 0.0f;
  scene.set_material(m);
  return scene;
}

// sat_spheres with a second light, a point light at the upper left.
inline Scene sat_spheres_and_a_point_light() {
  Scene scene = sat_spheres();
  Light point;
  point.type = LightType::Point;
  point.position = vec3(-30.0f, -40.0f, 45.0f);
  point.intensity = 4500.0f;
  scene.set_lights({scene.lights()[0], point});
  return scene;
}

}  // namespace penumbra::testing

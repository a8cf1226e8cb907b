// Renders a procedural volume through the installed library and checks that
// the image is not empty.
#include <penumbra/render/parameters.h>
#include <penumbra/scene/scene.h>
#include <penumbra/techniques/registry.h>
#include <penumbra/volume/procedural.h>

#include <cstdio>

int main() {
  using namespace penumbra;
  Scene scene;
  scene.set_volume(make_procedural_volume("spheres", ivec3(24)));
  scene.set_camera(Camera::framing(scene.volume().world_box()));
  scene.set_lights({Light{}});
  RenderSettings render;
  render.width = render.height = 16;
  scene.set_render(render);
  const TechniqueInfo& info = find_technique("shadow-rays");
  auto technique = info.create();
  technique->prepare(scene, ParameterValues(info.parameters));
  Image image;
  technique->render(scene, image);
  float sum = 0.0f;
  for (const vec4& p : image.pixels()) sum += p.r + p.g + p.b;
  std::printf("consumer: %dx%d image, sum %.3f\n", image.width(), image.height(), sum);
  return sum > 0.0f ? 0 : 1;
}

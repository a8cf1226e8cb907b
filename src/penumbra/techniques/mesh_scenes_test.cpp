// Every scene file in scenes/ that has meshes loads and renders with every
// technique that draws meshes, at 16^2 (issue 23: so that no mesh scene rots
// unseen), with the scene's own render.params as the CLI applies them.
#include "penumbra/analysis/image_metrics.h"
#include "penumbra/io/scene_json.h"
#include "penumbra/techniques/registry.h"
#include "test_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace penumbra {
namespace {

bool mentions_meshes(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str().find("\"meshes\"") != std::string::npos;
}

Image render_scene(const Scene& scene, const TechniqueInfo& info) {
  ParameterValues values(info.parameters);
  values.apply(scene.render().params, scene.render().technique == info.name, info.name);
  if (info.name == "pathtrace") {
    values.apply({{"spp", 4.0}, {"min_spp", 4.0}, {"target_error", 0.0}, {"progress", false}}, true);
  }
  auto technique = info.create();
  technique->prepare(scene, values);
  Image image;
  technique->render(scene, image);
  return image;
}

// Each mesh scene renders finite pixels with each technique that draws
// meshes, and the meshes show: the image differs from the same scene without
// them.
TEST(MeshScenes, EveryMeshSceneRendersWithEveryTechniqueThatDrawsMeshes) {
  int scenes = 0;
  for (const auto& entry : std::filesystem::directory_iterator(testing::source_dir() / "scenes")) {
    if (entry.path().extension() != ".json" || !mentions_meshes(entry.path())) continue;
    const std::string name = "scenes/" + entry.path().filename().string();
    const Scene scene = testing::repository_scene(name, 16);
    ASSERT_FALSE(scene.meshes().empty()) << name;
    Scene bare = scene;
    bare.set_meshes({});
    ++scenes;
    for (const TechniqueInfo& info : technique_registry()) {
      if (!info.draws_meshes) continue;
      const Image image = render_scene(scene, info);
      const Image without = render_scene(bare, info);
      bool finite = true;
      for (const vec4& p : image.pixels()) finite = finite && std::isfinite(p.r + p.g + p.b + p.a);
      EXPECT_TRUE(finite) << name << " with " << info.name;
      EXPECT_GT(rmse(image, without), 0.01) << name << " with " << info.name << ": the meshes do not show";
    }
  }
  EXPECT_GE(scenes, 4);  // knot-fbm, mesh-sphere, mesh-sphere-animated, sphere-texture-colour
}

}  // namespace
}  // namespace penumbra

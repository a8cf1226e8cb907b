// The "meshes" section of scene JSON: every key read, written back the same,
// and each kind of mistake named by its key.
#include "penumbra/base/error.h"
#include "penumbra/io/io_test_support.h"
#include "penumbra/io/scene_json.h"

#include <gtest/gtest.h>

namespace penumbra {
namespace {

std::string scene_with_meshes(const std::string& meshes) {
  return R"({"volume": {"builtin": "empty", "size": [8, 8, 8]}, "meshes": )" + meshes + "}";
}

std::string mesh_error_key(const std::string& meshes) {
  try {
    parse_scene(scene_with_meshes(meshes), std::filesystem::temp_directory_path());
  } catch (const InvalidScene& e) {
    return e.key();
  }
  return "";
}

TEST(SceneJsonMeshes, ReadsEveryKeyAndWritesThemBack) {
  const Scene scene = parse_scene(scene_with_meshes(R"([
    {"builtin": "torus", "resolution": 8, "scale": [2, 3, 4], "rotate_deg": [10, 20, 30], "translate": [1, 2, 3],
     "material": {"detail": {"type": "ridged", "frequency": 2.5, "octaves": 3, "lacunarity": 2.2, "gain": 0.4,
                             "offset": 0.9, "time": 1.5, "seed": 7},
                  "transfer_function": {"points": [[0, 1, 0, 0, 0.1], [1, 0, 1, 0, 0.5]], "range": [0, 2]},
                  "color_detail": {"type": "noise", "frequency": 4},
                  "color_transfer_function": {"points": [[0, 1, 0, 0, 0], [1, 0, 0, 1, 0]]},
                  "specular": 0.5, "roughness": 0.2, "transport_color": [0.8, 0.1, 0]}},
    {"builtin": "box"}])"),
                                  std::filesystem::temp_directory_path());
  ASSERT_EQ(scene.meshes().size(), 2u);
  const MeshObject& m = scene.meshes()[0];
  EXPECT_EQ(m.source.builtin, "torus");
  EXPECT_EQ(m.source.resolution, 8);
  EXPECT_EQ(m.scale, vec3(2.0f, 3.0f, 4.0f));
  EXPECT_EQ(m.rotate_deg, vec3(10.0f, 20.0f, 30.0f));
  EXPECT_EQ(m.translate, vec3(1.0f, 2.0f, 3.0f));
  const DetailFunction& d = m.material.detail;
  EXPECT_EQ(d.type, DetailType::Ridged);
  EXPECT_FLOAT_EQ(d.frequency, 2.5f);
  EXPECT_EQ(d.fractal.octaves, 3);
  EXPECT_FLOAT_EQ(d.fractal.lacunarity, 2.2f);
  EXPECT_FLOAT_EQ(d.fractal.gain, 0.4f);
  EXPECT_FLOAT_EQ(d.fractal.offset, 0.9f);
  EXPECT_TRUE(d.time_dependent);
  EXPECT_FLOAT_EQ(d.fractal.time, 1.5f);
  EXPECT_EQ(d.seed, 7u);
  EXPECT_EQ(m.material.tf.points().size(), 2u);
  EXPECT_FLOAT_EQ(m.material.specular, 0.5f);
  EXPECT_FLOAT_EQ(m.material.roughness, 0.2f);
  EXPECT_TRUE(m.material.has_color_detail);
  EXPECT_EQ(m.material.color_detail.type, DetailType::Noise);
  EXPECT_FLOAT_EQ(m.material.color_detail.frequency, 4.0f);
  EXPECT_EQ(m.material.color_tf.points().size(), 2u);
  EXPECT_FALSE(scene.meshes()[1].material.detail.time_dependent);
  EXPECT_FALSE(scene.meshes()[1].material.has_color_detail);
  ASSERT_TRUE(m.material.transport_color.has_value());
  EXPECT_EQ(*m.material.transport_color, vec3(0.8f, 0.1f, 0.0f));
  EXPECT_FALSE(scene.meshes()[1].material.transport_color.has_value());
  // The camera frames the meshes too: the torus (radius 1 x 4) reaches past the 8^3 box.
  EXPECT_GT(glm::length(scene.camera().eye - scene.camera().target), 10.0f);

  const Scene again = parse_scene(write_scene_json(scene), std::filesystem::temp_directory_path());
  EXPECT_EQ(write_scene_json(again), write_scene_json(scene));
  EXPECT_EQ(again.meshes()[0].mesh->triangles.size(), m.mesh->triangles.size());
}

TEST(SceneJsonMeshes, ReadsMeshFilesRelativeToTheScene) {
  test::TempDir dir;
  {
    std::ofstream obj(dir.path() / "tet.obj");
    obj << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  }
  {
    std::ofstream scene(dir.path() / "s.json");
    scene << scene_with_meshes(R"([{"file": "tet.obj", "material": {"detail": {"type": "constant", "value": 0.3}}}])");
  }
  const Scene scene = load_scene(dir.path() / "s.json");
  ASSERT_EQ(scene.meshes().size(), 1u);
  EXPECT_EQ(scene.meshes()[0].mesh->triangles.size(), 4u);
  EXPECT_EQ(scene.meshes()[0].source.file, "tet.obj");
  EXPECT_THROW(parse_scene(scene_with_meshes(R"([{"file": "missing.obj"}])"), dir.path()), IoError);
}

TEST(SceneJsonMeshes, NamesTheKeyAtFault) {
  EXPECT_EQ(mesh_error_key(R"({"builtin": "sphere"})"), "meshes");
  EXPECT_EQ(mesh_error_key(R"([{"builtin": "sphere", "colour": 1}])"), "meshes[0].colour");
  EXPECT_EQ(mesh_error_key(R"([{}])"), "meshes[0]");
  EXPECT_EQ(mesh_error_key(R"([{"builtin": "sphere", "material": {"color_transfer_function": {"points": []}}}])"),
            "meshes[0].material.color_transfer_function");
  EXPECT_EQ(mesh_error_key(R"([{"builtin": "sphere", "material": {"color_detail": {"type": "plaid"}}}])"),
            "meshes[0].material.color_detail.type");
  EXPECT_EQ(mesh_error_key(R"([{"builtin": "sphere", "file": "a.obj"}])"), "meshes[0]");
  EXPECT_EQ(mesh_error_key(R"([{"builtin": "teapot"}])"), "meshes[0].builtin");
  EXPECT_EQ(mesh_error_key(R"([{"builtin": "sphere", "resolution": 99}])"), "meshes[0].resolution");
  EXPECT_EQ(mesh_error_key(R"([{"file": "a.obj", "resolution": 2}])"), "meshes[0].resolution");
  EXPECT_EQ(mesh_error_key(R"([{"builtin": "box", "scale": [1, 0, 1]}])"), "meshes[0].scale");
  EXPECT_EQ(mesh_error_key(R"([{"builtin": "box", "material": {"detail": {"type": "marble"}}}])"),
            "meshes[0].material.detail.type");
  EXPECT_EQ(mesh_error_key(R"([{"builtin": "box", "material": {"detail": {"octaves": 0}}}])"),
            "meshes[0].material.detail.octaves");
  EXPECT_EQ(mesh_error_key(R"([{"builtin": "box", "material": {"detail": {"texture": "t.nrrd"}}}])"),
            "meshes[0].material.detail.texture");
  EXPECT_EQ(mesh_error_key(R"([{"builtin": "box", "material": {"detail": {"type": "texture"}}}])"),
            "meshes[0].material.detail.texture");
  EXPECT_EQ(mesh_error_key(R"([{"builtin": "box", "material": {"specular": 2}}])"), "meshes[0].material.specular");
  EXPECT_EQ(mesh_error_key(R"([{"builtin": "box", "material": {"roughness": 0}}])"), "meshes[0].material.roughness");
  EXPECT_EQ(mesh_error_key(R"([{"builtin": "box", "material": {"transport_color": [1, 0, 1.5]}}])"),
            "meshes[0].material.transport_color");
  EXPECT_EQ(mesh_error_key(R"([{"builtin": "box", "material": {"transport_color": [1, 0]}}])"),
            "meshes[0].material.transport_color");
  EXPECT_EQ(mesh_error_key(R"([{"builtin": "box", "material": {"transfer_function": {"points": []}}}])"),
            "meshes[0].material.transfer_function.points");
  std::string many = "[";
  for (int i = 0; i < 33; ++i) many += std::string(i ? "," : "") + R"({"builtin": "box"})";
  EXPECT_EQ(mesh_error_key(many + "]"), "meshes");
}

}  // namespace
}  // namespace penumbra

#include "server/scene_update.h"

#include "penumbra/base/error.h"
#include "server/http_error.h"
#include "server_test_support.h"

#include <gtest/gtest.h>

#include <fstream>

namespace penumbra::server {
namespace {

using nlohmann::json;
using testing::small_scene;
using testing::test_data_dir;

struct Fixture {
  DataDirectory data{test_data_dir()};
  VolumeCache cache;
  SceneLimits limits{64};
  ClientScene parse(const json& j) { return parse_client_scene(j, data, cache, limits); }
};

json file_scene(const std::string& file) {
  json j = small_scene();
  j["volume"] = {{"file", file}};
  return j;
}

// A closed tetrahedron, wound counter-clockwise seen from outside, as data/tet.obj.
void make_tet_obj() {
  std::ofstream(test_data_dir() / "tet.obj")
      << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
}

json mesh_scene(const json& meshes) {
  json j = small_scene("convolution");
  j["meshes"] = meshes;
  return j;
}

// The error parsing `scene` raises: "status key" ("400 meshes[0].file"), or "ok".
std::string error_of(Fixture& f, const json& scene) {
  try {
    f.parse(scene);
  } catch (const HttpError& e) {
    return std::to_string(e.status()) + " " + e.key();
  } catch (const InvalidScene& e) {
    return "InvalidScene " + e.key();
  }
  return "ok";
}

TEST(SceneUpdate, ReadsAVolumeFromTheDataFolderOnce) {
  Fixture f;
  const ClientScene a = f.parse(file_scene("tiny.nrrd"));
  EXPECT_EQ(a.scene.volume().dims(), ivec3(8, 6, 4));
  EXPECT_EQ(a.scene.volume_source().file, "tiny.nrrd");  // as the client named it, not the real path
  json moved = file_scene("tiny.nrrd");
  moved["camera"]["eye"] = {30, -30, 30};
  const ClientScene b = f.parse(moved);
  EXPECT_EQ(f.cache.loads(), 1u);
  EXPECT_EQ(a.scene.volume_ptr(), b.scene.volume_ptr());
}

TEST(SceneUpdate, TimeStepsShareTheLoadedSeries) {
  Fixture f;
  json j = file_scene("series.nrrd");
  j["volume"]["time_step"] = 1;
  const ClientScene one = f.parse(j);
  EXPECT_EQ(one.scene.time_step(), 1);
  j["volume"]["time_step"] = 0;
  EXPECT_EQ(f.parse(j).scene.time_step(), 0);
  EXPECT_EQ(f.cache.loads(), 1u);
  j["volume"]["time_step"] = 2;
  try {
    f.parse(j);
    ADD_FAILURE() << "time step 2 of 2 accepted";
  } catch (const InvalidScene& e) {
    EXPECT_EQ(e.key(), "volume.time_step");
  }
}

TEST(SceneUpdate, DefaultCameraFramesTheRealVolume) {
  Fixture f;
  json j = file_scene("tiny.nrrd");
  j.erase("camera");
  const ClientScene s = f.parse(j);
  const Camera expected = Camera::framing(s.scene.volume().world_box());
  EXPECT_NEAR(glm::distance(s.scene.camera().eye, expected.eye), 0.0f, 1e-4f);
  EXPECT_NEAR(glm::distance(s.scene.camera().target, expected.target), 0.0f, 1e-4f);
}

TEST(SceneUpdate, RefusesPresetFilesBigBuiltinsAndBadTechniqueParameters) {
  Fixture f;
  json preset = small_scene();
  preset["transfer_function"] = {{"preset", {{"file", "/etc/passwd"}}}};
  try {
    f.parse(preset);
    ADD_FAILURE();
  } catch (const InvalidScene& e) {
    EXPECT_EQ(e.key(), "transfer_function.preset");
  }
  json big = small_scene();
  big["volume"]["size"] = {65, 8, 8};
  try {
    f.parse(big);
    ADD_FAILURE();
  } catch (const HttpError& e) {
    EXPECT_EQ(e.status(), 413);
    EXPECT_EQ(e.key(), "volume.size");
  }
  json params = small_scene();
  params["render"]["params"] = {{"no_such_parameter", 1}};
  try {
    f.parse(params);
    ADD_FAILURE();
  } catch (const InvalidScene& e) {
    EXPECT_EQ(e.key(), "render.params.no_such_parameter");
  }
  json technique = small_scene();
  technique["render"]["technique"] = "no-such-technique";
  EXPECT_THROW(f.parse(technique), InvalidScene);
  EXPECT_THROW(f.parse(file_scene("../outside/secret.nrrd")), HttpError);
  EXPECT_THROW(f.parse(json::array()), InvalidScene);
}

TEST(SceneUpdate, ApplyingChangesOnlyTheVersionsOfChangedParts) {
  Fixture f;
  SceneState state;
  json j = small_scene();
  EXPECT_TRUE(state.apply(f.parse(j)));
  const SceneVersions before = state.scene().versions();

  j["camera"]["eye"] = {25, -40, 20};
  EXPECT_FALSE(state.apply(f.parse(j)));
  SceneVersions after = state.scene().versions();
  EXPECT_NE(after.camera, before.camera);
  EXPECT_EQ(after.lights, before.lights);
  EXPECT_EQ(after.transfer_function, before.transfer_function);
  EXPECT_EQ(after.data, before.data);
  EXPECT_EQ(after.render, before.render);

  j["lights"][0]["direction"] = {0, 0, -1};
  state.apply(f.parse(j));
  EXPECT_NE(state.scene().versions().lights, after.lights);
  EXPECT_EQ(state.scene().versions().transfer_function, after.transfer_function);

  // The same scene again changes nothing at all.
  const SceneVersions settled = state.scene().versions();
  state.apply(f.parse(j));
  const SceneVersions again = state.scene().versions();
  EXPECT_EQ(again.camera, settled.camera);
  EXPECT_EQ(again.lights, settled.lights);
  EXPECT_EQ(again.material, settled.material);
  EXPECT_EQ(again.geometry, settled.geometry);

  // Another volume replaces the data.
  EXPECT_TRUE(state.apply(f.parse(file_scene("tiny.nrrd"))));
  EXPECT_NE(state.scene().versions().data, settled.data);
  EXPECT_EQ(state.scene().volume().dims(), ivec3(8, 6, 4));
}

TEST(SceneUpdate, MeshFilesAndTexturesComeFromTheDataFolder) {
  make_tet_obj();
  Fixture f;
  const ClientScene s = f.parse(mesh_scene({{{"file", "tet.obj"}}}));
  ASSERT_EQ(s.scene.meshes().size(), 1u);
  EXPECT_EQ(s.scene.meshes()[0].mesh->triangles.size(), 4u);
  EXPECT_EQ(s.scene.meshes()[0].source.file, "tet.obj");  // as the client named it

  json textured = mesh_scene({{{"builtin", "sphere"},
                               {"material", {{"detail", {{"type", "texture"}, {"texture", "tiny.nrrd"}}}}}}});
  const ClientScene t = f.parse(textured);
  ASSERT_EQ(t.scene.meshes().size(), 1u);
  const DetailFunction& detail = t.scene.meshes()[0].material.detail;
  EXPECT_EQ(detail.texture_file, "tiny.nrrd");
  ASSERT_TRUE(detail.texture);
  EXPECT_EQ(detail.texture->dims(), ivec3(8, 6, 4));
}

TEST(SceneUpdate, MeshFilesOutsideTheDataFolderAreRefusedByKey) {
  make_tet_obj();
  Fixture f;
  EXPECT_EQ(error_of(f, mesh_scene({{{"file", "../x.obj"}}})), "400 meshes[0].file");
  EXPECT_EQ(error_of(f, mesh_scene({{{"file", "../outside/secret.nrrd"}}})), "400 meshes[0].file");
  EXPECT_EQ(error_of(f, mesh_scene({{{"file", (test_data_dir() / "tet.obj").string()}}})), "400 meshes[0].file");
  EXPECT_EQ(error_of(f, mesh_scene({{{"file", "/etc/passwd"}}})), "400 meshes[0].file");
  EXPECT_EQ(error_of(f, mesh_scene({{{"file", "linkdir/secret.obj"}}})), "403 meshes[0].file");
  EXPECT_EQ(error_of(f, mesh_scene({{{"file", "missing.obj"}}})), "404 meshes[0].file");
  EXPECT_EQ(error_of(f, mesh_scene({{{"file", "tiny.nrrd"}}})), "415 meshes[0].file");
  // The key names the mesh at fault.
  EXPECT_EQ(error_of(f, mesh_scene({{{"file", "tet.obj"}}, {{"file", "../tet.obj"}}})), "400 meshes[1].file");

  auto texture = [](const std::string& file) {
    return mesh_scene({{{"builtin", "sphere"}, {"material", {{"detail", {{"type", "texture"}, {"texture", file}}}}}}});
  };
  const std::string key = "meshes[0].material.detail.texture";
  EXPECT_EQ(error_of(f, texture("../outside/secret.nrrd")), "400 " + key);
  EXPECT_EQ(error_of(f, texture((test_data_dir().parent_path() / "outside" / "secret.nrrd").string())), "400 " + key);
  EXPECT_EQ(error_of(f, texture("escape.nrrd")), "403 " + key);
  EXPECT_EQ(error_of(f, texture("missing.nrrd")), "404 " + key);
  EXPECT_EQ(error_of(f, texture("tet.obj")), "415 " + key);  // a texture is a volume, not a mesh
  EXPECT_EQ(error_of(f, texture("tiny.nrrd")), "ok");
  // Builtin meshes need no data folder; their own keys are checked by the engine.
  EXPECT_EQ(error_of(f, mesh_scene({{{"builtin", "sphere"}, {"scale", 3}}})), "ok");
  EXPECT_EQ(error_of(f, mesh_scene({{{"builtin", "teapot"}}})), "InvalidScene meshes[0].builtin");
}

TEST(SceneUpdate, MeshEditsMoveOnlyTheMeshesVersion) {
  make_tet_obj();
  Fixture f;
  SceneState state;
  json j = mesh_scene({{{"builtin", "sphere"}, {"scale", 3}}});
  state.apply(f.parse(j));
  ASSERT_EQ(state.scene().meshes().size(), 1u);
  const SceneVersions before = state.scene().versions();

  auto expect_only_meshes_moved = [&](const SceneVersions& a, const SceneVersions& b) {
    EXPECT_NE(a.meshes, b.meshes);
    EXPECT_EQ(a.data, b.data);
    EXPECT_EQ(a.transfer_function, b.transfer_function);
    EXPECT_EQ(a.lights, b.lights);
    EXPECT_EQ(a.camera, b.camera);
    EXPECT_EQ(a.material, b.material);
    EXPECT_EQ(a.geometry, b.geometry);
    EXPECT_EQ(a.render, b.render);
  };

  j["meshes"][0]["translate"] = {1, 2, 3};
  EXPECT_FALSE(state.apply(f.parse(j)));
  const SceneVersions moved = state.scene().versions();
  expect_only_meshes_moved(moved, before);
  EXPECT_EQ(state.scene().meshes()[0].translate, vec3(1, 2, 3));

  j["meshes"].push_back({{"file", "tet.obj"}});
  state.apply(f.parse(j));
  const SceneVersions added = state.scene().versions();
  expect_only_meshes_moved(added, moved);
  EXPECT_EQ(state.scene().meshes().size(), 2u);

  // Edits elsewhere, or none at all, keep the meshes version.
  j["camera"]["eye"] = {25, -40, 20};
  state.apply(f.parse(j));
  EXPECT_EQ(state.scene().versions().meshes, added.meshes);
  EXPECT_NE(state.scene().versions().camera, added.camera);
  j["material"]["ambient"] = 0.2;
  state.apply(f.parse(j));
  EXPECT_EQ(state.scene().versions().meshes, added.meshes);
  state.apply(f.parse(j));
  EXPECT_EQ(state.scene().versions().meshes, added.meshes);

  // Removing the key removes the meshes.
  j.erase("meshes");
  state.apply(f.parse(j));
  EXPECT_TRUE(state.scene().meshes().empty());
  EXPECT_NE(state.scene().versions().meshes, added.meshes);
}

TEST(SceneUpdate, MeshFilesAndTexturesAreReadOnceForEverySession) {
  make_tet_obj();
  Fixture f;
  const json meshes = {{{"file", "tet.obj"},
                        {"material", {{"detail", {{"type", "texture"}, {"texture", "tiny.nrrd"}}}}}}};
  const ClientScene a = f.parse(mesh_scene(meshes));
  json moved = mesh_scene(meshes);
  moved["camera"]["eye"] = {30, -30, 30};
  const ClientScene b = f.parse(moved);  // a scene PUT that keeps its meshes, or another session
  EXPECT_EQ(f.cache.mesh_loads(), 1u);
  EXPECT_EQ(f.cache.texture_loads(), 1u);
  EXPECT_EQ(a.scene.meshes()[0].mesh, b.scene.meshes()[0].mesh);
  EXPECT_EQ(a.scene.meshes()[0].material.detail.texture, b.scene.meshes()[0].material.detail.texture);
}

// An error answer must not show where the server keeps its files.
void expect_relative_error(Fixture& f, const json& scene, int status, const std::string& key,
                           const std::string& starts_with) {
  try {
    f.parse(scene);
    ADD_FAILURE() << "accepted: " << scene.dump();
  } catch (const HttpError& e) {
    EXPECT_EQ(e.status(), status) << e.what();
    EXPECT_EQ(e.key(), key);
    EXPECT_EQ(std::string(e.what()).rfind(starts_with, 0), 0u) << e.what();
    EXPECT_EQ(std::string(e.what()).find(testing::test_data_root().string()), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find(std::filesystem::canonical(testing::test_data_root()).string()),
              std::string::npos)
        << e.what();
  }
}

TEST(SceneUpdate, FileErrorsNameTheKeyAndTheFileRelativeToTheDataFolder) {
  // A data folder of its own: the other tests list theirs.
  const std::filesystem::path root = testing::test_data_root() / "broken-data";
  std::filesystem::create_directories(root / "bad");
  std::ofstream(root / "bad" / "truncated.nrrd")
      << "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 8 8 8\nencoding: raw\n\nonly a few bytes";
  std::ofstream(root / "bad" / "huge.nrrd")
      << "NRRD0004\ntype: float\ndimension: 3\nsizes: 100000 100000 100000\nencoding: raw\n\n";
  std::ofstream(root / "bad" / "broken.obj") << "v 0 0 0\nf 1 2 x\n";
  Fixture f;
  f.data = DataDirectory(root);
  expect_relative_error(f, file_scene("bad/truncated.nrrd"), 422, "volume.file", "bad/truncated.nrrd: ");
  expect_relative_error(f, file_scene("bad/huge.nrrd"), 413, "volume.file", "voxel data");
  expect_relative_error(f, mesh_scene({{{"file", "bad/broken.obj"}}}), 422, "meshes[0].file", "bad/broken.obj: ");
  expect_relative_error(f,
                        mesh_scene({{{"builtin", "sphere"},
                                     {"material", {{"detail", {{"type", "texture"}, {"texture", "bad/truncated.nrrd"}}}}}}}),
                        422, "meshes[0].material.detail.texture", "bad/truncated.nrrd: ");
  // A failed load is not cached (the next request tries again); only the
  // builtin volume of the mesh scenes loaded.
  EXPECT_EQ(f.cache.loads(), 1u);
  EXPECT_EQ(f.cache.mesh_loads(), 0u);
  EXPECT_EQ(f.cache.texture_loads(), 0u);
}

}  // namespace
}  // namespace penumbra::server

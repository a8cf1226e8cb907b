#include "server/scene_update.h"

#include "penumbra/base/error.h"
#include "server/http_error.h"
#include "server_test_support.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace penumbra::server

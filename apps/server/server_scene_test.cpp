// Scenes and volumes over loopback: scene JSON round trip, loading another
// volume, the histogram and time steps, ParaView presets, meshes.
#include "penumbra/io/image_io.h"
#include "penumbra/scene/camera.h"
#include "server_test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

namespace penumbra::server {
namespace {

using nlohmann::json;
using testing::expect_error;
using testing::frame_body;
using testing::json_of;
using testing::session_path;
using testing::small_scene;

using ServerScenes = testing::ServerTest;

TEST_F(ServerScenes, SceneRoundTripsThroughPutAndGet) {
  const std::string id = server.create_session();
  json scene = small_scene("phong");
  scene["volume"] = {{"file", "tiny.nrrd"}};
  scene["lights"].push_back({{"type", "point"}, {"position", {10, 0, 5}}, {"intensity", 50.0}});
  scene["transfer_function"]["points"] = {{0.0, 0, 0, 0, 0}, {1.0, 1, 0.5, 0.25, 0.75}};
  auto c = server.client();
  const auto put = c.Put(session_path(id, "/scene").c_str(), scene.dump(), "application/json");
  ASSERT_TRUE(put);
  EXPECT_EQ(put->status, 200) << put->body;
  const auto got = c.Get(session_path(id, "/scene").c_str());
  ASSERT_TRUE(got);
  const json back = json::parse(got->body);
  EXPECT_EQ(back.at("volume").at("file"), "tiny.nrrd");
  EXPECT_EQ(back.at("lights").size(), 2u);
  EXPECT_EQ(back.at("lights")[1].at("type"), "point");
  EXPECT_EQ(back.at("render").at("technique"), "phong");
  EXPECT_EQ(back.at("transfer_function").at("points")[1][4], 0.75);
  // What GET returns is a scene the server accepts again unchanged.
  const auto again = c.Put(session_path(id, "/scene").c_str(), got->body, "application/json");
  ASSERT_TRUE(again);
  EXPECT_EQ(again->status, 200) << again->body;
  EXPECT_EQ(json_of(again).at("scene"), back);
}

TEST_F(ServerScenes, LoadingAVolumeReframesTheCameraAndKeepsTheLook) {
  json scene = small_scene();
  scene["planes"] = {{{"point", {0, 0, -9}}, {"normal", {0, 0, 1}}}};
  scene["lights"].push_back({{"type", "point"}, {"position", {0, 0, 16}}, {"intensity", 256.0}});
  const std::string id = server.create_session(scene);
  auto c = server.client();
  const auto r = c.Post(session_path(id, "/volume").c_str(), R"({"file": "sub/nested.nrrd"})", "application/json");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  const json body = json_of(r);
  EXPECT_EQ(body.at("scene").at("volume").at("file"), "sub/nested.nrrd");
  EXPECT_EQ(body.at("volume").at("dims"), json({8, 6, 4}));
  EXPECT_EQ(body.at("scene").at("planes").size(), 0u);
  EXPECT_EQ(body.at("scene").at("transfer_function"), json_of(c.Get(session_path(id, "/scene").c_str())).at("transfer_function"));
  // The TF is kept (to float precision: the scene holds floats).
  const json& kept = body.at("scene").at("transfer_function").at("points");
  const json& sent = scene.at("transfer_function").at("points");
  ASSERT_EQ(kept.size(), sent.size());
  for (std::size_t i = 0; i < sent.size(); ++i) {
    for (std::size_t c = 0; c < 5; ++c) EXPECT_NEAR(kept[i][c].get<double>(), sent[i][c].get<double>(), 1e-6);
  }
  // The point light moved with the box: the old box (16^3 voxels, diagonal
  // 15 sqrt 3) put it 16 above the centre; the new one (7 x 5 x 3) is smaller.
  const Camera framing = Camera::framing(Box3{vec3(-3.5f, -2.5f, -1.5f), vec3(3.5f, 2.5f, 1.5f)});
  const json eye = body.at("scene").at("camera").at("eye");
  EXPECT_NEAR(eye[0].get<float>(), framing.eye.x, 1e-3f);
  const float ratio = std::sqrt(49.0f + 25.0f + 9.0f) / (15.0f * std::sqrt(3.0f));
  EXPECT_NEAR(body.at("scene").at("lights")[1].at("position")[2].get<float>(), 16.0f * ratio, 1e-3f);
  expect_error(c.Post(session_path(id, "/volume").c_str(), R"({"builtin": "spheres", "size": [500, 8, 8]})",
                      "application/json"),
               413, "volume.size");
  expect_error(c.Post(session_path(id, "/volume").c_str(), R"({"builtin": "cubes"})", "application/json"), 400);
}

TEST_F(ServerScenes, VolumeInfoHasTheHistogramOfTheTfRangeAndTheTimeStep) {
  json scene = small_scene();
  scene["volume"] = {{"file", "tiny.nrrd"}};
  scene["transfer_function"]["range"] = "data";
  const std::string id = server.create_session(scene);
  auto c = server.client();
  json info = json_of(c.Get(session_path(id, "/volume").c_str()));
  EXPECT_EQ(info.at("value_range"), json({0.0, 191.0}));
  std::uint64_t total = 0;
  for (const json& n : info.at("histogram").at("counts")) total += n.get<std::uint64_t>();
  EXPECT_EQ(total, 192u);  // every voxel of tiny.nrrd lies in its data range
  EXPECT_EQ(info.at("histogram").at("range"), json({0.0, 191.0}));

  scene["transfer_function"]["range"] = {0, 95};
  ASSERT_EQ(c.Put(session_path(id, "/scene").c_str(), scene.dump(), "application/json")->status, 200);
  info = json_of(c.Get(session_path(id, "/volume").c_str()));
  EXPECT_EQ(info.at("histogram").at("above"), 96u);  // 96..191

  scene["volume"] = {{"file", "series.nrrd"}, {"time_step", 1}};
  scene["transfer_function"]["range"] = {0, 2};
  ASSERT_EQ(c.Put(session_path(id, "/scene").c_str(), scene.dump(), "application/json")->status, 200);
  info = json_of(c.Get(session_path(id, "/volume").c_str()));
  EXPECT_EQ(info.at("frames"), 2);
  EXPECT_EQ(info.at("time_step"), 1);
  EXPECT_EQ(info.at("histogram").at("counts")[192], 64u);  // 1.5 of [0, 2] in 256 bins
  scene["volume"]["time_step"] = 2;
  expect_error(c.Put(session_path(id, "/scene").c_str(), scene.dump(), "application/json"), 400, "volume.time_step");
}

TEST_F(ServerScenes, PresetsBecomeTransferFunctionPoints) {
  auto c = server.client();
  const std::string preset = R"([{"Name": "Two", "RGBPoints": [0, 0, 0, 0, 10, 1, 1, 1], "Points": [0, 0, 0.5, 0, 10, 1, 0.5, 0]}])";
  const json body = json_of(c.Post("/api/presets?name=Two", preset, "application/json"));
  const json& points = body.at("transfer_function").at("points");
  ASSERT_EQ(points.size(), 2u);
  EXPECT_EQ(points[0], json({0.0, 0.0, 0.0, 0.0, 0.0}));
  EXPECT_EQ(points[1], json({1.0, 1.0, 1.0, 1.0, 1.0}));
  expect_error(c.Post("/api/presets?name=Missing", preset, "application/json"), 422);
  expect_error(c.Post("/api/presets", "{", "application/json"), 422);
}

TEST_F(ServerScenes, MeshesComeFromTheDataFolderAndRenderWithConvolution) {
  // A closed tetrahedron, wound counter-clockwise seen from outside.
  std::ofstream(testing::test_data_dir() / "tet.obj")
      << "v 0 0 0\nv 4 0 0\nv 0 4 0\nv 0 0 4\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  const std::string id = server.create_session();
  auto c = server.client();
  auto put = [&](const json& scene) {
    return c.Put(session_path(id, "/scene").c_str(), scene.dump(), "application/json");
  };
  json scene = small_scene("convolution");
  scene["meshes"] = {{{"file", "tet.obj"}, {"translate", {-6, -6, -6}}},
                     {{"builtin", "sphere"}, {"scale", 3}, {"material", {{"detail", {{"type", "constant"}}}}}}};
  const auto ok = put(scene);
  ASSERT_TRUE(ok);
  ASSERT_EQ(ok->status, 200) << ok->body;
  const json meshes = json_of(ok).at("scene").at("meshes");
  ASSERT_EQ(meshes.size(), 2u);
  EXPECT_EQ(meshes[0].at("file"), "tet.obj");  // as the client named it, not the real path
  EXPECT_EQ(meshes[1].at("builtin"), "sphere");

  const auto r = frame(id, frame_body(16, 16, "png"));
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  EXPECT_EQ(r->get_header_value("X-Technique"), "convolution");
  const Image image = decode_png(std::span(reinterpret_cast<const std::uint8_t*>(r->body.data()), r->body.size()));
  EXPECT_EQ(image.width(), 16);
  EXPECT_EQ(image.height(), 16);
  // The meshes are drawn: without them the same view looks different.
  json plain = scene;
  plain.erase("meshes");
  ASSERT_EQ(put(plain)->status, 200);
  const auto without = frame(id, frame_body(16, 16, "png"));
  ASSERT_TRUE(without);
  ASSERT_EQ(without->status, 200) << without->body;
  EXPECT_NE(without->body, r->body) << "the meshes changed nothing in the frame";
  ASSERT_EQ(put(scene)->status, 200);

  // Files outside the folder, missing or of the wrong kind: a JSON error naming the key.
  json bad = scene;
  bad["meshes"][0]["file"] = "../x.obj";
  expect_error(put(bad), 400, "meshes[0].file");
  bad["meshes"][0]["file"] = (testing::test_data_dir() / "tet.obj").string();
  expect_error(put(bad), 400, "meshes[0].file");
  bad["meshes"][0]["file"] = "escape.nrrd";
  expect_error(put(bad), 403, "meshes[0].file");
  bad["meshes"][0]["file"] = "missing.obj";
  expect_error(put(bad), 404, "meshes[0].file");
  bad["meshes"][0]["file"] = "notes.txt";
  expect_error(put(bad), 415, "meshes[0].file");
  std::ofstream(testing::test_data_dir() / "broken.obj") << "v 0 0 0\nf 1 2 3\n";  // an index out of range
  bad["meshes"][0]["file"] = "broken.obj";
  expect_error(put(bad), 422);
  bad = scene;
  bad["meshes"][1]["material"]["detail"] = {{"type", "texture"}, {"texture", "../outside/secret.nrrd"}};
  expect_error(put(bad), 400, "meshes[1].material.detail.texture");
  bad["meshes"][1]["material"]["detail"]["texture"] = "linkdir/secret.nrrd";
  expect_error(put(bad), 403, "meshes[1].material.detail.texture");
  bad = scene;
  bad["meshes"][1]["builtin"] = "teapot";
  expect_error(put(bad), 400, "meshes[1].builtin");

  // A refused scene leaves the session's scene as it was.
  const json kept = json_of(c.Get(session_path(id, "/scene").c_str()));
  ASSERT_EQ(kept.at("meshes").size(), 2u);
  EXPECT_EQ(kept.at("meshes")[0].at("file"), "tet.obj");
}

}  // namespace
}  // namespace penumbra::server

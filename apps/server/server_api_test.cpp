// The server's listing and session endpoints over loopback: answers, error
// statuses with JSON bodies, path traversal, malformed and oversized requests.
#include "penumbra/base/error.h"
#include "penumbra/techniques/registry.h"
#include "server_test_support.h"

#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

namespace penumbra::server {
namespace {

using nlohmann::json;
using testing::expect_error;
using testing::frame_body;
using testing::json_of;
using testing::session_path;
using testing::small_scene;
using testing::TestServer;

using ServerApi = testing::ServerTest;

TEST_F(ServerApi, ServesTheViewer) {
  auto c = server.client();
  const auto index = c.Get("/");
  ASSERT_TRUE(index);
  EXPECT_EQ(index->status, 200);
  EXPECT_EQ(index->get_header_value("Content-Type"), "text/html; charset=utf-8");
  EXPECT_NE(index->body.find("<canvas"), std::string::npos);
  const auto script = c.Get("/main.js");
  ASSERT_TRUE(script);
  EXPECT_EQ(script->status, 200);
  EXPECT_EQ(script->get_header_value("Content-Type"), "text/javascript; charset=utf-8");
  expect_error(c.Get("/no-such-file.js"), 404);
  expect_error(c.Get("/../../etc/passwd"), 404);
  expect_error(c.Get("/%2e%2e/%2e%2e/etc/passwd"), 404);
  expect_error(c.Get("/api/nothing-here"), 404);
}

TEST_F(ServerApi, ListsEveryTechniqueWithItsParameterTable) {
  auto c = server.client();
  const json body = json_of(c.Get("/api/techniques"));
  const json& list = body.at("techniques");
  ASSERT_EQ(list.size(), technique_registry().size());
  for (std::size_t i = 0; i < list.size(); ++i) {
    const TechniqueInfo& info = technique_registry()[i];
    EXPECT_EQ(list[i].at("name"), info.name);
    EXPECT_EQ(list[i].at("summary"), info.summary);
    ASSERT_EQ(list[i].at("parameters").size(), info.parameters.specs().size()) << info.name;
    for (const json& p : list[i].at("parameters")) {
      const ParameterSpec& spec = info.parameters.at(p.at("name").get<std::string>());
      EXPECT_EQ(p.at("type"), spec.type_name());
      EXPECT_EQ(p.at("doc"), spec.doc);
      if (spec.type == ParameterType::Float || spec.type == ParameterType::Int) {
        EXPECT_LE(p.at("min").get<double>(), p.at("default").get<double>()) << spec.name;
        EXPECT_GE(p.at("max").get<double>(), p.at("default").get<double>()) << spec.name;
      }
      if (spec.type == ParameterType::Choice) {
        EXPECT_EQ(p.at("choices").get<std::vector<std::string>>(), spec.choices);
      }
    }
  }
}

TEST_F(ServerApi, ListsVolumesInsideTheDataFolderOnly) {
  auto c = server.client();
  const json body = json_of(c.Get("/api/volumes"));
  std::vector<std::string> paths;
  for (const json& f : body.at("files")) paths.push_back(f.at("path"));
  EXPECT_EQ(paths, (std::vector<std::string>{"inside_link.nrrd", "series.nrrd", "sub/nested.nrrd", "tiny.nrrd"}));
  EXPECT_TRUE(body.at("data_folder").get<bool>());
  bool spheres = false;
  for (const json& b : body.at("builtins")) spheres = spheres || b.at("name") == "spheres";
  EXPECT_TRUE(spheres);
}

TEST_F(ServerApi, NewSessionsStartFromTheInitialScene) {
  auto c = server.client();
  const auto r = c.Post("/api/sessions", "", "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 201);
  const json body = json_of(r);
  EXPECT_EQ(body.at("id").get<std::string>().size(), 32u);
  EXPECT_EQ(body.at("scene").at("volume").at("builtin"), "spheres");
  EXPECT_EQ(body.at("volume").at("dims"), json({16, 16, 16}));
  EXPECT_EQ(body.at("volume").at("histogram").at("counts").size(), 256u);
  // Two sessions are two different ids.
  EXPECT_NE(server.create_session(), server.create_session());
}

TEST_F(ServerApi, PathTraversalIsRefusedAndTheServerCarriesOn) {
  const std::string id = server.create_session();
  auto c = server.client();
  const auto load = [&](const json& volume) {
    return c.Post(session_path(id, "/volume").c_str(), volume.dump(), "application/json");
  };
  expect_error(load({{"file", "../outside/secret.nrrd"}}), 400, "volume.file");
  expect_error(load({{"file", "sub/../../outside/secret.nrrd"}}), 400, "volume.file");
  expect_error(load({{"file", (testing::test_data_root() / "outside" / "secret.nrrd").string()}}), 400, "volume.file");
  expect_error(load({{"file", "/etc/passwd"}}), 400, "volume.file");
  expect_error(load({{"file", "escape.nrrd"}}), 403, "volume.file");
  expect_error(load({{"file", "linkdir/secret.nrrd"}}), 403, "volume.file");
  expect_error(load({{"file", "notes.txt"}}), 415, "volume.file");
  expect_error(load({{"file", "missing.nrrd"}}), 404, "volume.file");
  expect_error(load({{"file", 7}}), 400, "volume.file");
  // The same through a whole scene, and through a preset file in a scene.
  json scene = small_scene();
  scene["volume"] = {{"file", "../outside/secret.nrrd"}};
  expect_error(c.Put(session_path(id, "/scene").c_str(), scene.dump(), "application/json"), 400, "volume.file");
  scene = small_scene();
  scene["transfer_function"] = {{"preset", {{"file", "../../etc/passwd"}}}};
  expect_error(c.Put(session_path(id, "/scene").c_str(), scene.dump(), "application/json"), 400,
               "transfer_function.preset");
  // The session still has its scene and the server still answers.
  EXPECT_EQ(json::parse(c.Get(session_path(id, "/scene").c_str())->body).at("volume").at("builtin"), "spheres");
  EXPECT_EQ(c.Get("/api/techniques")->status, 200);
}

TEST_F(ServerApi, MalformedRequestsGetJsonErrors) {
  const std::string id = server.create_session();
  auto c = server.client();
  const std::string scene_path = session_path(id, "/scene");
  expect_error(c.Put(scene_path.c_str(), "{", "application/json"), 400, "body");
  expect_error(c.Put(scene_path.c_str(), "", "application/json"), 400, "body");
  expect_error(c.Put(scene_path.c_str(), "[1, 2]", "application/json"), 400);
  json unknown = small_scene();
  unknown["lightz"] = json::array();
  expect_error(c.Put(scene_path.c_str(), unknown.dump(), "application/json"), 400, "lightz");
  json bad_light = small_scene();
  bad_light["lights"][0]["direction"] = {0, 0};
  expect_error(c.Put(scene_path.c_str(), bad_light.dump(), "application/json"), 400, "lights[0].direction");
  json bad_param = small_scene();
  bad_param["render"]["params"] = {{"shadow_density_scale", -5.0}};
  expect_error(c.Put(scene_path.c_str(), bad_param.dump(), "application/json"), 400,
               "render.params.shadow_density_scale");

  expect_error(frame(id, "not json"), 400, "body");
  expect_error(frame(id, R"({"width": "big", "height": 8})"), 400, "width");
  expect_error(frame(id, R"({"width": 0, "height": 8})"), 400, "width");
  expect_error(frame(id, R"({"width": 100000, "height": 8})"), 400, "width");
  expect_error(frame(id, R"({"width": 8, "height": 8, "format": "gif"})"), 400, "format");
  expect_error(frame(id, R"({"width": 8, "height": 8, "quality": 0})"), 400, "quality");
  expect_error(frame(id, R"({"width": 8, "height": 8, "colour": 1})"), 400, "colour");
  expect_error(c.Get(session_path(id, "/frame?width=abc").c_str()), 400, "width");
  expect_error(c.Get(session_path(id, "/frame?width=8&colour=red").c_str()), 400, "colour");
  expect_error(c.Post("/api/sessions", R"({"scenery": {}})", "application/json"), 400, "scenery");

  expect_error(c.Get("/api/sessions/0123456789abcdef/scene"), 404, "session");
  expect_error(frame("0123456789abcdef", frame_body(8, 8)), 404, "session");
}

TEST_F(ServerApi, OversizedBodiesAreRefused) {
  ServerOptions options = TestServer::default_options();
  options.max_request_bytes = 1024;
  TestServer small(options);
  auto c = small.client();
  const auto r = c.Post("/api/sessions", std::string(4096, ' '), "application/json");
  expect_error(r, 413);
  EXPECT_EQ(c.Get("/api/techniques")->status, 200);
}

TEST_F(ServerApi, APortInUseIsAnError) {
  ServerOptions options = TestServer::default_options();
  options.port = server.port();
  HttpServer second(options);
  EXPECT_THROW(second.bind(), IoError);
  EXPECT_EQ(server.client().Get("/api/techniques")->status, 200);
}

// httplib listens with a backlog of 5: on a busy machine a burst of
// connections overflowed it and some got a reset instead of an answer (the
// load test's frame bursts; ServerOptions::listen_backlog).
TEST_F(ServerApi, TheListenBacklogIsRaisedAboveHttplibsFive) {
  ServerOptions options = TestServer::default_options();
  options.listen_backlog = 64;
  TestServer raised(options);
  EXPECT_EQ(raised.server().listen_backlog(), 64);
  EXPECT_GE(server.server().listen_backlog(), 128);  // the default, 1024, or net.core.somaxconn
}

TEST_F(ServerApi, GarbageOnTheSocketDoesNotStopTheServer) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  ASSERT_GE(fd, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(std::uint16_t(server.port()));
  ::inet_pton(AF_INET, "127.0.0.1", &address.sin_addr);
  ASSERT_EQ(::connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
  const std::string garbage = "\x01\x02 NOT HTTP AT ALL\r\n\r\n";
  ASSERT_EQ(::send(fd, garbage.data(), garbage.size(), 0), ssize_t(garbage.size()));
  char reply[256];
  (void)::recv(fd, reply, sizeof reply, 0);  // a 400 or a closed connection, either is fine
  ::close(fd);
  auto c = server.client();
  EXPECT_EQ(c.Get("/api/techniques")->status, 200);
}

TEST_F(ServerApi, DeletedSessionsAreGone) {
  const std::string id = server.create_session();
  auto c = server.client();
  EXPECT_EQ(c.Delete(session_path(id, "").c_str())->status, 200);
  expect_error(c.Delete(session_path(id, "").c_str()), 404, "session");
  expect_error(c.Get(session_path(id, "/scene").c_str()), 404, "session");
}

}  // namespace
}  // namespace penumbra::server

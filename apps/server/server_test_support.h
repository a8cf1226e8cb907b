#pragma once
// Support for the server tests: a data folder with small volumes (and paths
// that try to escape it), a server on a free loopback port, small scenes and
// image decoding.
#include "penumbra/render/image.h"
#include "server/http_server.h"

#include <gtest/gtest.h>
#include <httplib.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <memory>
#include <string>

namespace penumbra::server::testing {

// Created once per test process under the temp folder:
//   data/tiny.nrrd          8x6x4 uint8, voxel i has value i (0..191)
//   data/series.nrrd        4x4x4 float32, 2 time steps (frame f holds f + 0.5)
//   data/sub/nested.nrrd    a copy of tiny.nrrd one folder down
//   data/inside_link.nrrd   symlink to tiny.nrrd (stays inside: allowed)
//   data/escape.nrrd        symlink to ../outside/secret.nrrd (leaves: refused)
//   data/linkdir            symlink to ../outside (a folder outside)
//   data/notes.txt          not a volume
//   outside/secret.nrrd     a volume outside the data folder
const std::filesystem::path& test_data_root();  // the folder holding data/ and outside/
std::filesystem::path test_data_dir();          // data/

// A builtin-spheres scene small enough to render in milliseconds.
nlohmann::json small_scene(const std::string& technique = "shadow-rays", int volume_size = 16);

class TestServer {
 public:
  explicit TestServer(ServerOptions options = default_options());
  ~TestServer();

  static ServerOptions default_options();  // port 0, test_data_dir(), small limits

  httplib::Client client() const;
  HttpServer& server() { return *server_; }
  int port() const { return port_; }

  // POST /api/sessions (with `scene` unless null); returns the id.
  std::string create_session(const nlohmann::json& scene = nullptr) const;
  // POST /api/sessions/ID/frame with a frame_body().
  httplib::Result post_frame(const std::string& id, const std::string& body) const;

 private:
  std::unique_ptr<HttpServer> server_;
  int port_ = 0;
};

// A server per test, for the endpoint test suites.
class ServerTest : public ::testing::Test {
 protected:
  httplib::Result frame(const std::string& id, const std::string& body) { return server.post_frame(id, body); }
  TestServer server;
};

nlohmann::json json_of(const httplib::Result& result);
// Checks an error answer: the status, a JSON body saying what went wrong and,
// when given, the key it names.
void expect_error(const httplib::Result& result, int status, const std::string& key = "");
// "/api/sessions/ID" + rest
std::string session_path(const std::string& id, const std::string& rest);
// {"width":w,"height":h,"format":f} plus `extra` keys.
std::string frame_body(int width, int height, const std::string& format = "png",
                       const nlohmann::json& extra = nlohmann::json::object());
// Decodes a baseline JPEG to 8-bit RGB; returns width/height through the refs.
std::vector<std::uint8_t> decode_jpeg(const std::string& bytes, int& width, int& height);

}  // namespace penumbra::server::testing

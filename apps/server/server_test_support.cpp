#include "server_test_support.h"

#include "penumbra/io/volume_writer.h"

#include <gtest/gtest.h>

// jpeglib.h needs FILE and size_t declared before it.
#include <cstdio>
#include <jpeglib.h>

#include <stdexcept>
#include <unistd.h>

namespace penumbra::server::testing {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

void make_test_data(const fs::path& root) {
  fs::remove_all(root);
  fs::create_directories(root / "data" / "sub");
  fs::create_directories(root / "outside");
  Volume tiny(ivec3(8, 6, 4), VoxelType::UInt8);
  auto* v = tiny.frame_as<std::uint8_t>(0);
  for (int i = 0; i < 8 * 6 * 4; ++i) v[i] = std::uint8_t(i);
  write_nrrd(root / "data" / "tiny.nrrd", tiny);
  write_nrrd(root / "data" / "sub" / "nested.nrrd", tiny);
  write_nrrd(root / "outside" / "secret.nrrd", tiny);
  Volume series(ivec3(4), VoxelType::Float32, 2);
  for (int f = 0; f < 2; ++f) {
    float* s = series.frame_as<float>(f);
    for (int i = 0; i < 64; ++i) s[i] = float(f) + 0.5f;
  }
  write_nrrd(root / "data" / "series.nrrd", series);
  fs::create_symlink("tiny.nrrd", root / "data" / "inside_link.nrrd");
  fs::create_symlink("../outside/secret.nrrd", root / "data" / "escape.nrrd");
  fs::create_directory_symlink("../outside", root / "data" / "linkdir");
  std::FILE* notes = std::fopen((root / "data" / "notes.txt").c_str(), "w");
  std::fputs("not a volume\n", notes);
  std::fclose(notes);
}

}  // namespace

const fs::path& test_data_root() {
  static const fs::path root = [] {
    const fs::path p = fs::temp_directory_path() / ("penumbra-server-test-" + std::to_string(::getpid()));
    make_test_data(p);
    return p;
  }();
  return root;
}

fs::path test_data_dir() { return test_data_root() / "data"; }

json small_scene(const std::string& technique, int volume_size) {
  json scene = json::parse(R"({
    "volume": {"builtin": "spheres", "size": [16, 16, 16]},
    "transfer_function": {"points": [[0.0, 1, 1, 1, 0.0], [0.2, 0.9, 0.5, 0.2, 0.0], [0.3, 0.9, 0.5, 0.2, 0.5],
                                     [1.0, 1.0, 0.9, 0.8, 0.95]], "range": [0, 1]},
    "camera": {"eye": [20, -40, 20], "target": [0, 0, 0], "up": [0, 0, 1], "fov_deg": 30},
    "lights": [{"type": "directional", "direction": [0.4, 0.5, -1.0], "intensity": 1.5}],
    "material": {"ambient": 0.1},
    "render": {"width": 32, "height": 32, "step": 0.5, "technique": "shadow-rays"},
    "background": [0.05, 0.05, 0.1]
  })");
  scene["volume"]["size"] = {volume_size, volume_size, volume_size};
  scene["render"]["technique"] = technique;
  return scene;
}

ServerOptions TestServer::default_options() {
  ServerOptions o;
  o.port = 0;
  o.data_dir = test_data_dir();
  o.initial_scene = small_scene().dump();
  o.http_threads = 16;
  o.max_image_side = 512;
  o.max_builtin_size = 64;
  return o;
}

TestServer::TestServer(ServerOptions options) : server_(std::make_unique<HttpServer>(std::move(options))) {
  port_ = server_->start();
}

TestServer::~TestServer() { server_->stop(); }

httplib::Client TestServer::client() const {
  httplib::Client c("127.0.0.1", port_);
  c.set_read_timeout(60);
  c.set_write_timeout(60);
  return c;
}

std::string TestServer::create_session(const json& scene) const {
  auto c = client();
  const std::string body = scene.is_null() ? "{}" : json{{"scene", scene}}.dump();
  const auto r = c.Post("/api/sessions", body, "application/json");
  if (!r || r->status != 201) throw std::runtime_error("cannot create a session: " + (r ? r->body : "no answer"));
  return json::parse(r->body).at("id").get<std::string>();
}

json json_of(const httplib::Result& result) {
  if (!result) return json();
  EXPECT_EQ(result->get_header_value("Content-Type"), "application/json") << result->body;
  return json::parse(result->body, nullptr, false);
}

void expect_error(const httplib::Result& r, int status, const std::string& key) {
  ASSERT_TRUE(r) << "no answer";
  EXPECT_EQ(r->status, status) << r->body;
  const json body = json_of(r);
  ASSERT_TRUE(body.is_object()) << r->body;
  EXPECT_TRUE(body.contains("error")) << r->body;
  EXPECT_EQ(body.value("status", 0), status);
  if (!key.empty()) {
    EXPECT_EQ(body.value("key", ""), key) << r->body;
  }
}

std::string session_path(const std::string& id, const std::string& rest) { return "/api/sessions/" + id + rest; }

httplib::Result TestServer::post_frame(const std::string& id, const std::string& body) const {
  return client().Post(session_path(id, "/frame").c_str(), body, "application/json");
}

std::string frame_body(int width, int height, const std::string& format, const json& extra) {
  json body{{"width", width}, {"height", height}, {"format", format}};
  body.update(extra);
  return body.dump();
}

std::vector<std::uint8_t> decode_jpeg(const std::string& bytes, int& width, int& height) {
  jpeg_decompress_struct info{};
  jpeg_error_mgr errors{};
  info.err = jpeg_std_error(&errors);
  jpeg_create_decompress(&info);
  jpeg_mem_src(&info, reinterpret_cast<const unsigned char*>(bytes.data()), static_cast<unsigned long>(bytes.size()));
  jpeg_read_header(&info, TRUE);
  info.out_color_space = JCS_RGB;
  jpeg_start_decompress(&info);
  width = int(info.output_width);
  height = int(info.output_height);
  std::vector<std::uint8_t> rgb(std::size_t(width) * std::size_t(height) * 3);
  while (info.output_scanline < info.output_height) {
    JSAMPROW row = rgb.data() + std::size_t(info.output_scanline) * std::size_t(width) * 3;
    jpeg_read_scanlines(&info, &row, 1);
  }
  jpeg_finish_decompress(&info);
  jpeg_destroy_decompress(&info);
  return rgb;
}

}  // namespace penumbra::server::testing

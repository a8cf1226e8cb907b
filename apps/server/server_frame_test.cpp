// Frames over loopback: PNG identical to the engine's image, JPEG, previews,
// rebuilds across frames, every technique, the progressive stream.
#include "penumbra/analysis/image_metrics.h"
#include "penumbra/io/image_io.h"
#include "penumbra/io/scene_json.h"
#include "penumbra/techniques/registry.h"
#include "server/image_encoding.h"
#include "server_test_support.h"

#include <gtest/gtest.h>

namespace penumbra::server {
namespace {

using nlohmann::json;
using testing::expect_error;
using testing::frame_body;
using testing::json_of;
using testing::session_path;
using testing::small_scene;

using ServerFrames = testing::ServerTest;

TEST_F(ServerFrames, PngFramesAreExactlyTheEnginesImage) {
  const json scene = small_scene();
  const std::string id = server.create_session(scene);
  const auto r = frame(id, frame_body(40, 30, "png"));
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  EXPECT_EQ(r->get_header_value("Content-Type"), "image/png");
  EXPECT_EQ(r->get_header_value("X-Technique"), "shadow-rays");
  EXPECT_FALSE(r->get_header_value("X-Render-Ms").empty());
  const Image served = decode_png(std::span(reinterpret_cast<const std::uint8_t*>(r->body.data()), r->body.size()));
  ASSERT_EQ(served.width(), 40);
  ASSERT_EQ(served.height(), 30);

  // The same scene rendered directly by the engine, at the same size.
  Scene direct = parse_scene(scene.dump(), ".");
  RenderSettings settings = direct.render();
  settings.width = 40;
  settings.height = 30;
  direct.set_render(settings);
  const TechniqueInfo& info = find_technique("shadow-rays");
  auto technique = info.create();
  technique->prepare(direct, ParameterValues(info.parameters));
  Image expected;
  technique->render(direct, expected);
  // Lossless: every 8-bit code is the same (rendering is deterministic).
  EXPECT_EQ(to_srgb8(served), to_srgb8(expected));
  double sum = 0.0;
  for (const vec4& p : expected.pixels()) sum += p.r + p.g + p.b;
  EXPECT_GT(sum / double(expected.pixel_count()), 0.05) << "the test scene renders black";
}

TEST_F(ServerFrames, JpegFramesAndQueryFrames) {
  const std::string id = server.create_session();
  const auto r = frame(id, frame_body(48, 32, "jpeg", {{"quality", 70}}));
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  EXPECT_EQ(r->get_header_value("Content-Type"), "image/jpeg");
  int w = 0, h = 0;
  testing::decode_jpeg(r->body, w, h);
  EXPECT_EQ(w, 48);
  EXPECT_EQ(h, 32);
  auto c = server.client();
  const auto q = c.Get(session_path(id, "/frame?width=20&height=10&format=png").c_str());
  ASSERT_TRUE(q);
  ASSERT_EQ(q->status, 200) << q->body;
  const Image image = decode_png(std::span(reinterpret_cast<const std::uint8_t*>(q->body.data()), q->body.size()));
  EXPECT_EQ(image.width(), 20);
  EXPECT_EQ(image.height(), 10);
}

// Found by fuzz_server: an error that echoes a query parameter's name which
// is not UTF-8 made the JSON error body itself throw while being written.
TEST_F(ServerFrames, ErrorsEchoingBytesThatAreNotUtf8StillAnswerInJson) {
  const std::string id = server.create_session();
  auto c = server.client();
  const auto r = c.Get(session_path(id, "/frame?width=16&w%FFdth=16").c_str());
  expect_error(r, 400);
  EXPECT_NE(json_of(r).value("key", "").find("w"), std::string::npos);
}

TEST_F(ServerFrames, ACameraAloneMovesTheView) {
  const std::string id = server.create_session();
  const auto first = frame(id, frame_body(32, 32));
  const json camera{{"eye", {-40, -20, 20}}, {"target", {0, 0, 0}}, {"up", {0, 0, 1}}, {"fov_deg", 30}};
  const auto moved = frame(id, frame_body(32, 32, "png", {{"camera", camera}}));
  ASSERT_TRUE(first && moved);
  ASSERT_EQ(moved->status, 200) << moved->body;
  EXPECT_NE(first->body, moved->body);
  auto c = server.client();
  const json scene = json::parse(c.Get(session_path(id, "/scene").c_str())->body);
  EXPECT_EQ(scene.at("camera").at("eye"), json({-40.0, -20.0, 20.0}));
  EXPECT_EQ(scene.at("render").at("technique"), "shadow-rays");  // the rest of the scene stays
  expect_error(frame(id, frame_body(32, 32, "png", {{"camera", {{"eye", {0, 0, 0}}, {"target", {0, 0, 0}}}}})), 400);
  expect_error(frame(id, frame_body(32, 32, "png", {{"camera", 5}})), 400, "camera");
}

TEST_F(ServerFrames, PreviewFramesUseACoarserStep) {
  const std::string id = server.create_session();
  const auto full = frame(id, frame_body(32, 32));
  const auto preview = frame(id, frame_body(32, 32, "png", {{"preview", true}, {"step_scale", 4}}));
  ASSERT_TRUE(full && preview);
  EXPECT_EQ(std::stof(full->get_header_value("X-Step")), 0.5f);
  EXPECT_EQ(std::stof(preview->get_header_value("X-Step")), 2.0f);
  EXPECT_LT(std::stoull(preview->get_header_value("X-Samples")), std::stoull(full->get_header_value("X-Samples")));
}

TEST_F(ServerFrames, CameraMovesRebuildNothingAndLightMovesRebuildShadows) {
  json scene = small_scene();
  scene["render"]["params"] = {{"shadow_cache", true}};
  const std::string id = server.create_session(scene);
  const auto rebuilds = [&](const json& s) {
    const auto r = frame(id, frame_body(16, 16, "jpeg", {{"scene", s}}));
    EXPECT_EQ(r->status, 200) << r->body;
    return std::stoi(r->get_header_value("X-Rebuilds"));
  };
  const int first = rebuilds(scene);
  EXPECT_GE(first, 1);
  scene["camera"]["eye"] = {-20, -40, 20};
  EXPECT_EQ(rebuilds(scene), first);
  scene["transfer_function"]["points"][2][4] = 0.6;  // the shadow cache depends on the TF
  EXPECT_EQ(rebuilds(scene), first + 1);
  scene["lights"][0]["direction"] = {-0.4, 0.5, -1.0};
  EXPECT_EQ(rebuilds(scene), first + 2);
  EXPECT_EQ(rebuilds(scene), first + 2);  // nothing changed
}

TEST_F(ServerFrames, SwitchingBackToARecentTechniqueKeepsItsStructures) {
  json scene = small_scene();
  scene["render"]["params"] = {{"shadow_cache", true}};
  const std::string id = server.create_session(scene);
  const auto rebuilds_with = [&](const std::string& technique) {
    scene["render"]["technique"] = technique;
    scene["render"]["params"] = technique == "shadow-rays" ? json{{"shadow_cache", true}} : json::object();
    const auto r = frame(id, frame_body(16, 16, "jpeg", {{"scene", scene}}));
    EXPECT_EQ(r->status, 200) << r->body;
    return std::stoi(r->get_header_value("X-Rebuilds"));
  };
  EXPECT_EQ(rebuilds_with("shadow-rays"), 1);
  scene["lights"][0]["direction"] = {0, 0.5, -1};
  EXPECT_EQ(rebuilds_with("shadow-rays"), 2);      // the light moved: rebuilt
  rebuilds_with("phong");
  EXPECT_EQ(rebuilds_with("shadow-rays"), 2);      // the same instance, nothing rebuilt
  rebuilds_with("phong");
  rebuilds_with("emission-absorption");            // a third technique drops the oldest (shadow-rays)
  EXPECT_EQ(rebuilds_with("shadow-rays"), 1);      // a new instance, built once
}

TEST_F(ServerFrames, TechniquesSwitchPerFrame) {
  json scene = small_scene();
  const std::string id = server.create_session(scene);
  for (const TechniqueInfo& info : technique_registry()) {
    scene["render"]["technique"] = info.name;
    scene["render"]["params"] = json::object();
    const auto r = frame(id, frame_body(16, 16, "jpeg", {{"scene", scene}}));
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 200) << info.name << ": " << r->body;
    EXPECT_EQ(r->get_header_value("X-Technique"), info.name);
  }
  scene["render"]["technique"] = "no-such-technique";
  expect_error(frame(id, frame_body(16, 16, "jpeg", {{"scene", scene}})), 400, "render.technique");
}

TEST_F(ServerFrames, ProgressiveStreamGoesFromCoarseToFull) {
  const std::string id = server.create_session();
  auto c = server.client();
  const auto r = c.Get(session_path(id, "/progressive?width=64&height=64").c_str());
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  EXPECT_EQ(r->get_header_value("Content-Type"), "multipart/x-mixed-replace; boundary=penumbra-frame");
  // Parts in order: 16x16, 32x32, 64x64 JPEGs, then the closing boundary.
  std::vector<int> widths;
  std::size_t at = 0;
  while ((at = r->body.find("Content-Length: ", at)) != std::string::npos) {
    const std::size_t length = std::stoul(r->body.substr(at + 16));
    const std::size_t start = r->body.find("\r\n\r\n", at) + 4;
    int w = 0, h = 0;
    testing::decode_jpeg(r->body.substr(start, length), w, h);
    widths.push_back(w);
    EXPECT_EQ(w, h);
    at = start + length;
  }
  EXPECT_EQ(widths, (std::vector<int>{16, 32, 64}));
  EXPECT_NE(r->body.find("--penumbra-frame--"), std::string::npos);
  expect_error(c.Get("/api/sessions/0123456789abcdef/progressive?width=64&height=64"), 404, "session");
}

// pathtrace in the server is progressive: frames of an unchanged scene add
// to one estimate, which X-Spp counts; a change starts it again.
TEST_F(ServerFrames, PathtraceFramesOfAnUnchangedSceneReportGrowingSampleCounts) {
  json scene = small_scene("pathtrace");
  scene["render"]["params"] = {{"spp", 2}, {"min_spp", 2}, {"max_total_spp", 6}};
  const std::string id = server.create_session(scene);
  const auto spp = [&](const json& s, std::string* converged = nullptr) {
    const auto r = frame(id, frame_body(16, 16, "png", {{"scene", s}}));
    EXPECT_EQ(r->status, 200) << r->body;
    if (converged) *converged = r->get_header_value("X-Converged");
    return std::stoi(r->get_header_value("X-Spp"));
  };
  std::string converged;
  EXPECT_EQ(spp(scene, &converged), 2);
  EXPECT_EQ(converged, "0");
  EXPECT_EQ(spp(scene), 4);
  EXPECT_EQ(spp(scene, &converged), 6);
  EXPECT_EQ(converged, "1");  // at max_total_spp
  EXPECT_EQ(spp(scene), 6);
  scene["camera"]["eye"] = {-20, -40, 20};
  EXPECT_EQ(spp(scene), 2);
  EXPECT_EQ(spp(scene), 4);
  scene["lights"][0]["intensity"] = 1.2;
  EXPECT_EQ(spp(scene), 2);
  // A preview (coarser step) is another state; the full frame after it too.
  const auto preview = frame(id, frame_body(16, 16, "png", {{"scene", scene}, {"preview", true}}));
  EXPECT_EQ(preview->get_header_value("X-Spp"), "2");
  EXPECT_EQ(spp(scene), 2);
  // A client may turn it off: every frame is then spp paths of its own.
  scene["render"]["params"]["progressive"] = false;
  EXPECT_EQ(spp(scene), 2);
  EXPECT_EQ(spp(scene, &converged), 2);
  EXPECT_EQ(converged, "1");
  // Other techniques send no sample count.
  scene["render"]["technique"] = "shadow-rays";
  scene["render"]["params"] = json::object();
  const auto other = frame(id, frame_body(16, 16, "png", {{"scene", scene}}));
  EXPECT_FALSE(other->has_header("X-Spp"));
}

// The viewer's light "size" control sends a distant light's angle_deg (or a
// sphere's or disk's radius) in the scene; the techniques that follow the
// light's size render it differently, and bad sizes are 400s naming the key.
TEST_F(ServerFrames, ALightSizeUpdateChangesTheSceneLightAndTheFrame) {
  json scene = small_scene("cone-shadows", 32);
  scene["lights"][0] = {{"type", "distant"}, {"direction", {0.4, 0.5, -1.0}}, {"intensity", 1.5}, {"angle_deg", 0}};
  const std::string id = server.create_session(scene);
  for (const json& technique : {json{{"cone-shadows", json::object()}},
                                json{{"shadow-rays", {{"light_samples", 16}}}},
                                json{{"pathtrace", {{"spp", 4}, {"min_spp", 2}}}}}) {
    const std::string name = technique.begin().key();
    SCOPED_TRACE(name);
    scene["render"]["technique"] = name;
    scene["render"]["params"] = technique.begin().value();
    scene["lights"][0]["angle_deg"] = 0;
    const auto hard = frame(id, frame_body(24, 24, "png", {{"scene", scene}}));
    scene["lights"][0]["angle_deg"] = 20;
    const auto soft = frame(id, frame_body(24, 24, "png", {{"scene", scene}}));
    ASSERT_TRUE(hard && soft);
    ASSERT_EQ(soft->status, 200) << soft->body;
    if (name == "pathtrace") {
      EXPECT_EQ(soft->get_header_value("X-Spp"), "4");  // started again
    }
    const Image a = decode_png(std::span(reinterpret_cast<const std::uint8_t*>(hard->body.data()), hard->body.size()));
    const Image b = decode_png(std::span(reinterpret_cast<const std::uint8_t*>(soft->body.data()), soft->body.size()));
    EXPECT_GT(max_abs_error(a, b), 0.02) << "the light's size changes the frame";
  }
  auto c = server.client();
  const json stored = json::parse(c.Get(session_path(id, "/scene").c_str())->body);
  EXPECT_EQ(stored.at("lights").at(0).at("angle_deg"), 20.0);

  scene["lights"][0]["angle_deg"] = 95;
  expect_error(frame(id, frame_body(16, 16, "png", {{"scene", scene}})), 400, "lights[0].angle_deg");
  scene["lights"][0]["angle_deg"] = "wide";
  expect_error(frame(id, frame_body(16, 16, "png", {{"scene", scene}})), 400, "lights[0].angle_deg");
  scene["lights"][0] = {{"type", "sphere"}, {"position", {30, 30, 30}}, {"intensity", 2000}, {"radius", -1}};
  expect_error(frame(id, frame_body(16, 16, "png", {{"scene", scene}})), 400, "lights[0].radius");
  scene["lights"][0] = {{"type", "directional"}, {"direction", {0.4, 0.5, -1.0}}, {"angle_deg", 3}};
  expect_error(frame(id, frame_body(16, 16, "png", {{"scene", scene}})), 400, "lights[0].angle_deg");
}

}  // namespace
}  // namespace penumbra::server

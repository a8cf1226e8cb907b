// Several clients at once: parallel sessions render correctly, a render in
// progress does not hold up other clients' cheap requests, stale frames are
// superseded and a full queue answers 503. Renders are held back with the
// queue's start hook instead of relying on timing.
#include "server/render_queue.h"
#include "server_test_support.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <future>
#include <thread>

namespace penumbra::server {
namespace {

using namespace std::chrono_literals;
using nlohmann::json;
using testing::frame_body;
using testing::small_scene;
using testing::TestServer;
using testing::expect_error;

// Holds every job that starts on a render worker until released.
class Gate {
 public:
  explicit Gate(RenderQueue& queue) : queue_(queue), released_(release_.get_future().share()) {
    queue_.set_start_hook([this] {
      ++held_;
      released_.wait();
    });
  }
  ~Gate() { open(); }
  void open() {
    if (!opened_.exchange(true)) release_.set_value();
    queue_.set_start_hook(nullptr);
  }
  // Waits (bounded) until `n` jobs are held.
  bool wait_held(int n) {
    for (int i = 0; i < 10000 && held_.load() < n; ++i) std::this_thread::sleep_for(1ms);
    return held_.load() >= n;
  }

 private:
  RenderQueue& queue_;
  std::promise<void> release_;
  std::shared_future<void> released_;
  std::atomic<int> held_{0};
  std::atomic<bool> opened_{false};
};

httplib::Result post_frame(const TestServer& server, const std::string& id, const std::string& body) {
  auto c = server.client();
  return c.Post(("/api/sessions/" + id + "/frame").c_str(), body, "application/json");
}

TEST(ServerConcurrency, ManyClientsRenderTheirOwnScenesAtOnce) {
  ServerOptions options = TestServer::default_options();
  options.max_waiting_renders = 64;
  TestServer server(options);
  constexpr int kClients = 6;
  std::vector<std::future<std::string>> clients;
  for (int i = 0; i < kClients; ++i) {
    clients.push_back(std::async(std::launch::async, [&server, i]() -> std::string {
      json scene = small_scene(i % 2 ? "phong" : "shadow-rays");
      const std::string id = server.create_session(scene);
      for (int frame = 0; frame < 3; ++frame) {
        scene["camera"]["eye"] = {20 + 5 * frame, -40, 20};
        const int size = 16 + 4 * i;  // each client its own size, to catch mix-ups
        const auto r = post_frame(server, id, frame_body(size, size, "jpeg", {{"scene", scene}}));
        if (!r) return "no answer";
        if (r->status != 200) return r->body;
        int w = 0, h = 0;
        testing::decode_jpeg(r->body, w, h);
        if (w != size || h != size) return "wrong size";
        if (r->get_header_value("X-Technique") != scene["render"]["technique"]) return "wrong technique";
      }
      return "ok";
    }));
  }
  for (auto& c : clients) EXPECT_EQ(c.get(), "ok");
}

TEST(ServerConcurrency, ARenderInProgressDoesNotBlockOtherClients) {
  TestServer server;
  const std::string slow = server.create_session();
  const std::string other = server.create_session();
  Gate gate(server.server().render_queue());
  auto held = std::async(std::launch::async, [&] { return post_frame(server, slow, frame_body(32, 32)); });
  ASSERT_TRUE(gate.wait_held(1));
  // While that render is held on its worker, other clients are served.
  auto c = server.client();
  EXPECT_EQ(c.Get("/api/techniques")->status, 200);
  EXPECT_EQ(c.Get("/api/volumes")->status, 200);
  EXPECT_EQ(c.Get("/")->status, 200);
  EXPECT_EQ(c.Get(("/api/sessions/" + other + "/scene").c_str())->status, 200);
  EXPECT_EQ(c.Get(("/api/sessions/" + other + "/volume").c_str())->status, 200);
  // ... and so is the slow session's own snapshot.
  EXPECT_EQ(c.Get(("/api/sessions/" + slow + "/scene").c_str())->status, 200);
  EXPECT_EQ(held.wait_for(0s), std::future_status::timeout) << "the held render finished early";
  gate.open();
  const auto r = held.get();
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
}

TEST(ServerConcurrency, NewerFramesSupersedeWaitingOnes) {
  ServerOptions options = TestServer::default_options();
  options.render_workers = 1;
  TestServer server(options);
  const std::string id = server.create_session();
  json scene = small_scene();
  Gate gate(server.server().render_queue());
  auto first = std::async(std::launch::async, [&] { return post_frame(server, id, frame_body(16, 16, "jpeg", {{"scene", scene}})); });
  ASSERT_TRUE(gate.wait_held(1));
  auto second = std::async(std::launch::async, [&] { return post_frame(server, id, frame_body(16, 16, "jpeg", {{"scene", scene}})); });
  for (int i = 0; i < 5000 && server.server().render_queue().waiting() < 1; ++i) std::this_thread::sleep_for(1ms);
  scene["camera"]["eye"] = {-20, -40, 20};
  auto third = std::async(std::launch::async, [&] { return post_frame(server, id, frame_body(16, 16, "jpeg", {{"scene", scene}})); });
  const auto superseded = second.get();  // answered without waiting for the held render
  ASSERT_TRUE(superseded);
  EXPECT_EQ(superseded->status, 409) << superseded->body;
  gate.open();
  EXPECT_EQ(first.get()->status, 200);
  EXPECT_EQ(third.get()->status, 200);
}

TEST(ServerConcurrency, AFullQueueAnswers503AndRecovers) {
  ServerOptions options = TestServer::default_options();
  options.render_workers = 1;
  options.max_waiting_renders = 2;
  TestServer server(options);
  std::vector<std::string> ids;
  for (int i = 0; i < 4; ++i) ids.push_back(server.create_session());
  Gate gate(server.server().render_queue());
  auto running = std::async(std::launch::async, [&] { return post_frame(server, ids[0], frame_body(16, 16)); });
  ASSERT_TRUE(gate.wait_held(1));
  auto waiting_1 = std::async(std::launch::async, [&] { return post_frame(server, ids[1], frame_body(16, 16)); });
  auto waiting_2 = std::async(std::launch::async, [&] { return post_frame(server, ids[2], frame_body(16, 16)); });
  for (int i = 0; i < 5000 && server.server().render_queue().waiting() < 2; ++i) std::this_thread::sleep_for(1ms);
  const auto refused = post_frame(server, ids[3], frame_body(16, 16));
  ASSERT_TRUE(refused);
  EXPECT_EQ(refused->status, 503);
  EXPECT_NE(refused->body.find("busy"), std::string::npos);
  gate.open();
  EXPECT_EQ(running.get()->status, 200);
  EXPECT_EQ(waiting_1.get()->status, 200);
  EXPECT_EQ(waiting_2.get()->status, 200);
  EXPECT_EQ(post_frame(server, ids[3], frame_body(16, 16))->status, 200);
}

// A server that holds two sessions, evicting one for a third only when it
// has been idle for `grace`.
ServerOptions two_sessions(std::chrono::seconds grace) {
  ServerOptions options = TestServer::default_options();
  options.max_sessions = 2;
  options.session_eviction_grace = grace;
  return options;
}

TEST(ServerConcurrency, OldSessionsAreEvictedBeyondTheLimit) {
  TestServer server(two_sessions(std::chrono::seconds(0)));
  const std::string a = server.create_session();
  const std::string b = server.create_session();
  const std::string c = server.create_session();
  auto client = server.client();
  EXPECT_EQ(client.Get(("/api/sessions/" + a + "/scene").c_str())->status, 404);
  EXPECT_EQ(client.Get(("/api/sessions/" + b + "/scene").c_str())->status, 200);
  EXPECT_EQ(client.Get(("/api/sessions/" + c + "/scene").c_str())->status, 200);
}

TEST(ServerConcurrency, SessionsInUseAreNotEvictedToMakeRoom) {
  TestServer server(two_sessions(std::chrono::seconds(60)));
  const std::string a = server.create_session();
  const std::string b = server.create_session();
  auto client = server.client();
  const auto refused = client.Post("/api/sessions", "{}", "application/json");
  expect_error(refused, 503, "session");
  EXPECT_EQ(client.Get(("/api/sessions/" + a + "/scene").c_str())->status, 200);
  EXPECT_EQ(client.Get(("/api/sessions/" + b + "/scene").c_str())->status, 200);
  // Once one is deleted there is room again.
  EXPECT_EQ(client.Delete(("/api/sessions/" + a).c_str())->status, 200);
  EXPECT_EQ(client.Post("/api/sessions", "{}", "application/json")->status, 201);
}

TEST(ServerConcurrency, IdleSessionsExpire) {
  ServerOptions options = TestServer::default_options();
  options.session_idle_timeout = std::chrono::seconds(0);
  TestServer server(options);
  const std::string id = server.create_session();
  std::this_thread::sleep_for(2ms);
  auto client = server.client();
  const auto r = client.Get(("/api/sessions/" + id + "/scene").c_str());
  EXPECT_EQ(r->status, 404);
  EXPECT_NE(r->body.find("expired"), std::string::npos);
}

}  // namespace
}  // namespace penumbra::server

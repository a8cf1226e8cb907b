#pragma once
// `penumbra serve`: the HTTP server behind the web viewer (apps/web), on
// cpp-httplib. Endpoints (all errors are 4xx/5xx with a JSON body
// {"error", "key", "status"}):
//
//   GET    /                                the viewer (embedded files)
//   GET    /api/techniques                  techniques with their parameter tables
//   GET    /api/volumes                     volume files under --data, builtin volumes
//   POST   /api/presets[?name=N]            ParaView preset JSON -> TF points
//   POST   /api/sessions                    new session (optional {"scene": ...}) -> {"id", "scene", "volume"}
//   DELETE /api/sessions/ID
//   GET    /api/sessions/ID/scene           scene JSON v1
//   PUT    /api/sessions/ID/scene           replace it (scene JSON v1) -> {"scene", "volume"}
//   GET    /api/sessions/ID/volume          dims, range, frames, histogram of the TF range
//   POST   /api/sessions/ID/volume          {"file": path} | {"builtin": name, "size": [...]}
//   POST   /api/sessions/ID/frame           {"scene"?, "camera"?, "width", "height", "preview"?,
//                                            "step_scale"?, "format"?, "quality"?}
//   GET    /api/sessions/ID/frame?width=&height=&format=&quality=&preview=
//   GET    /api/sessions/ID/progressive?width=&height=   multipart/x-mixed-replace: coarse to full
//
// A frame renders the session's scene, after applying the request's "scene"
// (scene JSON v1) and then its "camera" (the scene's camera section) when
// given; only the parts that changed are rebuilt. Unknown keys and query
// parameters are errors.
// Frames come back as image/jpeg or image/png with X-Prepare-Ms, X-Render-Ms,
// X-Encode-Ms, X-Samples, X-Rebuilds, X-Technique and X-Step headers; a
// pathtrace frame also with X-Spp (paths per pixel of the estimate it shows)
// and X-Converged (1 once more frames would add nothing). pathtrace runs
// progressively here: frames of an unchanged scene (and size and technique
// parameters) keep adding spp paths per pixel to one estimate, up to
// max_total_spp; any change starts it again.
// Renders, volume loads and scene changes run on a RenderQueue, so httplib's
// handler threads stay free for other clients' cheap requests.
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

namespace penumbra::server {

class RenderQueue;

struct ServerOptions {
  std::string host = "127.0.0.1";
  int port = 8080;  // 0: any free port (see HttpServer::port)
  std::filesystem::path data_dir;  // empty: no data folder, builtin volumes only
  // Scene JSON v1 for new sessions, volume paths relative to data_dir; empty:
  // the builtin spheres.
  std::string initial_scene;
  int render_workers = 2;
  int max_waiting_renders = 16;
  int max_waiting_renders_per_session = 4;  // so one client's flood cannot fill the queue
  int http_threads = 48;  // idle keep-alive connections hold one each
  // Connections the kernel queues for the accept loop. httplib listens with
  // a backlog of 5 (compiled into Debian's libcpp-httplib). A burst of
  // connections while the accept thread waits for a busy CPU overflows it:
  // the kernel drops SYNs (the client retries 1 s, 3 s later) or answers with
  // SYN cookies, and some of those connections were reset after the client
  // had sent its request, which then got no answer at all (docs/RELIABILITY.md,
  // the load test). bind() raises it to this; the kernel caps it at
  // net.core.somaxconn.
  int listen_backlog = 1024;
  std::size_t max_sessions = 16;
  std::chrono::seconds session_idle_timeout{3600};
  // A session used within this long is never evicted to make room for a new
  // one: with max_sessions all that recent, POST /api/sessions answers 503,
  // so a flood of new sessions cannot push out viewers that are in use.
  std::chrono::seconds session_eviction_grace{30};
  // What the sessions' technique structures and images may hold together
  // (session_memory.h); 0: the process's memory budget.
  std::uint64_t session_memory_bytes = 0;
  int max_image_side = 2048;
  int max_builtin_size = 256;
  std::size_t max_request_bytes = std::size_t(8) << 20;
};

class HttpServer {
 public:
  explicit HttpServer(ServerOptions options);
  ~HttpServer();  // stops the server
  HttpServer(const HttpServer&) = delete;
  HttpServer& operator=(const HttpServer&) = delete;

  // Binds the socket; returns the port. Throws IoError when it cannot bind.
  int bind();
  // Serves until stop() (binds first if needed).
  void serve();
  // bind() + serve() on a background thread; returns the port.
  int start();
  void stop();

  int port() const;
  // The listening socket's backlog as the kernel reports it (Linux), -1
  // before bind() or where unknown.
  int listen_backlog() const;
  const ServerOptions& options() const;
  RenderQueue& render_queue();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The default scene of a new session when ServerOptions::initial_scene is
// empty: the builtin spheres with a TF, one light and shadow rays.
const char* default_initial_scene();

}  // namespace penumbra::server

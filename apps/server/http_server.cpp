#include "server/http_server.h"

#include "penumbra/base/error.h"
#include "server/routes.h"
#include "server/server_context.h"

#include <fmt/format.h>
#include <httplib.h>

#include <thread>

#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/socket.h>

namespace penumbra::server {

struct HttpServer::Impl {
  explicit Impl(ServerOptions options) : context(std::move(options)) {}

  ServerContext context;
  httplib::Server http;
  int port = -1;
  int listen_fd = -1;  // the socket httplib listens on, as its socket options callback saw it
  std::thread thread;
};

HttpServer::HttpServer(ServerOptions options) : impl_(std::make_unique<Impl>(std::move(options))) {
  const ServerOptions& o = impl_->context.options;
  const int threads = std::max(4, o.http_threads);
  impl_->http.new_task_queue = [threads] { return new httplib::ThreadPool(std::size_t(threads)); };
  impl_->http.set_payload_max_length(o.max_request_bytes);
  // Short keep-alive: an idle browser connection holds a handler thread.
  impl_->http.set_keep_alive_timeout(2);
  impl_->http.set_read_timeout(10);
  impl_->http.set_write_timeout(30);
  // httplib's default also sets SO_REUSEPORT, which lets a second server
  // bind the same port and take half of the connections (and sessions). The
  // callback runs for the listening socket only, before it binds; bind()
  // raises that socket's backlog afterwards.
  impl_->http.set_socket_options([impl = impl_.get()](int socket) {
    const int yes = 1;
    ::setsockopt(socket, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
    impl->listen_fd = socket;
  });
  add_routes(impl_->http, impl_->context);
}

HttpServer::~HttpServer() { stop(); }

int HttpServer::bind() {
  if (impl_->port >= 0) return impl_->port;
  const ServerOptions& o = impl_->context.options;
  if (o.port < 0 || o.port > 65535) throw InvalidArgument("--port", fmt::format("must be in [0, 65535], got {}", o.port));
  if (o.port == 0) {
    impl_->port = impl_->http.bind_to_any_port(o.host);
  } else if (impl_->http.bind_to_port(o.host, o.port)) {
    impl_->port = o.port;
  }
  if (impl_->port <= 0) {
    impl_->port = -1;
    throw IoError(fmt::format("{}:{}", o.host, o.port), "cannot listen there (address in use or not local?)");
  }
  // listen() again on a listening socket sets its backlog (see
  // ServerOptions::listen_backlog for why httplib's 5 is too few).
  if (impl_->listen_fd < 0 || ::listen(impl_->listen_fd, std::max(o.listen_backlog, 5)) != 0) {
    impl_->port = -1;
    throw IoError(fmt::format("{}:{}", o.host, o.port), "cannot set the listen backlog");
  }
  return impl_->port;
}

void HttpServer::serve() {
  bind();
  impl_->http.listen_after_bind();
}

int HttpServer::start() {
  const int port = bind();
  impl_->thread = std::thread([this] { impl_->http.listen_after_bind(); });
  // Requests made right after start() must not race the accept loop.
  for (int i = 0; i < 5000 && !impl_->http.is_running(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  return port;
}

void HttpServer::stop() {
  impl_->http.stop();
  if (impl_->thread.joinable()) impl_->thread.join();
}

int HttpServer::port() const { return impl_->port; }

int HttpServer::listen_backlog() const {
  if (impl_->port < 0 || impl_->listen_fd < 0) return -1;
#ifdef __linux__
  // For a listening socket TCP_INFO reports the backlog in tcpi_sacked.
  tcp_info info{};
  socklen_t size = sizeof info;
  if (::getsockopt(impl_->listen_fd, IPPROTO_TCP, TCP_INFO, &info, &size) == 0 && info.tcpi_state == TCP_LISTEN) {
    return int(info.tcpi_sacked);
  }
#endif
  return -1;
}

const ServerOptions& HttpServer::options() const { return impl_->context.options; }

RenderQueue& HttpServer::render_queue() { return impl_->context.queue; }

const char* default_initial_scene() {
  return R"({
  "volume": {"builtin": "spheres", "size": [64, 64, 64]},
  "transfer_function": {"points": [[0.0, 1.0, 1.0, 1.0, 0.0], [0.2, 0.9, 0.5, 0.2, 0.0], [0.3, 0.9, 0.5, 0.2, 0.3],
                                   [1.0, 1.0, 0.9, 0.8, 0.9]], "range": [0, 1]},
  "camera": {"eye": [75, -145, 80], "target": [0, 0, -6], "up": [0, 0, 1], "fov_deg": 30},
  "lights": [{"type": "directional", "direction": [0.4, 0.5, -1.0], "intensity": 1.6}],
  "material": {"shading": "phase", "ambient": 0.15},
  "render": {"width": 512, "height": 512, "step": 0.5, "technique": "shadow-rays"},
  "background": [0.02, 0.02, 0.03]
})";
}

}  // namespace penumbra::server

// penumbra serve [--port 8080] [--host 127.0.0.1] [--data DIR]: the web viewer
// (apps/server, apps/web). New sessions open the engine CT when the data
// folder has it, else the builtin spheres.
#include "cli_common.h"
#include "commands.h"

#include "penumbra/base/error.h"
#include "server/http_server.h"

#include <fmt/format.h>

#include <csignal>
#include <cstdio>
#include <filesystem>
#include <memory>

namespace penumbra::cli {

extern const char* const kEngineSceneText;

namespace {

struct ServeOptions {
  int port = 8080;
  std::string host = "127.0.0.1";
  std::string data;
  int render_workers = 2;
};

server::HttpServer* running_server = nullptr;

// stop() only shuts the listening socket down, which is safe in a signal
// handler; serve() then returns and the server is destroyed normally.
void on_signal(int) {
  if (running_server) running_server->stop();
}

void run_serve(const ServeOptions& options) {
  server::ServerOptions o;
  o.host = options.host;
  o.port = options.port;
  o.render_workers = options.render_workers;
  if (!options.data.empty()) {
    if (!std::filesystem::is_directory(options.data)) {
      throw InvalidArgument("--data", fmt::format("'{}' is not a folder", options.data));
    }
    o.data_dir = options.data;
  } else if (const auto found = find_data_dir()) {
    o.data_dir = *found;
  }
  if (!o.data_dir.empty() && std::filesystem::exists(o.data_dir / "engine_256x256x128_uint8.nhdr")) {
    // The demo scene names its volume relative to scenes/; the server wants
    // it relative to the data folder.
    std::string text = kEngineSceneText;
    const std::string prefix = "../../shared/data/";
    if (const auto at = text.find(prefix); at != std::string::npos) text.erase(at, prefix.size());
    o.initial_scene = text;
  }
  auto http = std::make_unique<server::HttpServer>(o);
  const int port = http->bind();
  fmt::print("penumbra serve: http://{}:{}/ (data: {})\n", o.host, port,
             o.data_dir.empty() ? std::string("none, builtin volumes only") : o.data_dir.string());
  std::fflush(stdout);
  running_server = http.get();
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  http->serve();
  running_server = nullptr;
}

}  // namespace

void add_serve_command(CLI::App& app) {
  auto options = std::make_shared<ServeOptions>();
  CLI::App* cmd = app.add_subcommand("serve", "serve the web viewer over HTTP (open the printed address in a browser)");
  cmd->add_option("--port", options->port, "TCP port (0 = any free port, printed at start)")
      ->check(CLI::Range(0, 65535))
      ->capture_default_str();
  cmd->add_option("--host", options->host, "address to listen on (0.0.0.0 = every interface)")->capture_default_str();
  cmd->add_option("--data", options->data, "folder of volumes the viewer may open (default: ../shared/data if present)");
  cmd->add_option("--render-workers", options->render_workers, "renders that run at once (each uses every core)")
      ->check(CLI::Range(1, 16))
      ->capture_default_str();
  cmd->callback([options] { run_serve(*options); });
}

}  // namespace penumbra::cli

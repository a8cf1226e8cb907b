#include "server/routes.h"

#include "penumbra/base/error.h"
#include "penumbra/io/paraview_preset.h"
#include "server/api_json.h"
#include "server/frame_request.h"
#include "server/http_error.h"
#include "server/http_responses.h"
#include "server/server_context.h"
#include "server/web_assets.h"

#include <fmt/format.h>
#include <httplib.h>
#include <nlohmann/json.hpp>

#include <memory>

namespace penumbra::server {
namespace {

using httplib::Request;
using httplib::Response;
using nlohmann::json;

const char* const kSessionPattern = "/api/sessions/([0-9a-f]{1,64})";

// Runs `work` as a job of the session on the render queue and waits for it.
// The handler thread only waits; the queue bounds how many can wait at once.
void run_job(ServerContext& context, const std::shared_ptr<Session>& session, bool replaceable,
             std::function<void()> work) {
  context.queue.submit(session->id(), replaceable, [session, work = std::move(work)] { work(); }).get();
}

json scene_and_volume(const Session& session) {
  return {{"scene", json::parse(session.scene_json())}, {"volume", session.volume_info()}};
}

void add_frame_headers(Response& res, const Frame& frame) {
  res.set_header("Cache-Control", "no-store");
  res.set_header("X-Prepare-Ms", fmt::format("{:.2f}", frame.prepare_ms));
  res.set_header("X-Render-Ms", fmt::format("{:.2f}", frame.render_ms));
  res.set_header("X-Encode-Ms", fmt::format("{:.2f}", frame.encode_ms));
  res.set_header("X-Samples", std::to_string(frame.samples));
  res.set_header("X-Rebuilds", std::to_string(frame.rebuilds));
  res.set_header("X-Technique", frame.technique);
  res.set_header("X-Step", fmt::format("{}", frame.step));
  if (frame.spp > 0) {
    res.set_header("X-Spp", std::to_string(frame.spp));
    res.set_header("X-Converged", frame.converged ? "1" : "0");
  }
}

Frame render_frame(ServerContext& context, const std::shared_ptr<Session>& session, const FrameRequest& request) {
  Frame frame;
  // A frame that carries the whole scene makes any older one still waiting
  // for this session pointless.
  run_job(context, session, request.scene.has_value(), [&] { frame = session->render(request); });
  return frame;
}

void send_frame(Response& res, const Frame& frame) {
  add_frame_headers(res, frame);
  res.set_content(reinterpret_cast<const char*>(frame.bytes.data()), frame.bytes.size(),
                  std::string(mime_type(frame.format)).c_str());
}

// multipart/x-mixed-replace: each part replaces the previous one in the
// browser, so the client sees a coarse frame at once and the full one when it
// is ready. Levels: 1/4 size with 4x the step, 1/2 size with 2x, full.
void stream_progressive(ServerContext& context, const std::shared_ptr<Session>& session, FrameRequest request,
                        Response& res) {
  struct Stream {
    std::vector<FrameRequest> levels;
    std::size_t next = 0;
  };
  auto stream = std::make_shared<Stream>();
  for (const int divisor : {4, 2, 1}) {
    FrameRequest level = request;
    level.width = std::max(1, request.width / divisor);
    level.height = std::max(1, request.height / divisor);
    level.preview = divisor > 1;
    level.step_scale = float(divisor);
    if (divisor > 1 && (level.width < 16 || level.height < 16)) continue;
    stream->levels.push_back(level);
  }
  // The first level is rendered before the response starts, so that a bad
  // request still gets a JSON error instead of a broken stream.
  auto first = std::make_shared<Frame>(render_frame(context, session, stream->levels.front()));
  const std::string boundary = "penumbra-frame";
  res.set_header("Cache-Control", "no-store");
  res.set_chunked_content_provider(
      "multipart/x-mixed-replace; boundary=" + boundary,
      [&context, session, stream, first, boundary](std::size_t, httplib::DataSink& sink) {
        Frame frame;
        try {
          if (stream->next == 0) {
            frame = std::move(*first);
          } else {
            frame = render_frame(context, session, stream->levels[stream->next]);
          }
        } catch (...) {
          return false;  // the connection closes; the client keeps the last part
        }
        const std::string head = fmt::format(
            "--{}\r\nContent-Type: {}\r\nContent-Length: {}\r\nX-Level: {}\r\nX-Width: {}\r\nX-Height: {}\r\n"
            "X-Render-Ms: {:.2f}\r\n\r\n",
            boundary, mime_type(frame.format), frame.bytes.size(), stream->next, frame.width, frame.height,
            frame.render_ms);
        if (!sink.write(head.data(), head.size()) ||
            !sink.write(reinterpret_cast<const char*>(frame.bytes.data()), frame.bytes.size()) ||
            !sink.write("\r\n", 2)) {
          return false;
        }
        if (++stream->next == stream->levels.size()) {
          const std::string tail = "--" + boundary + "--\r\n";
          sink.write(tail.data(), tail.size());
          sink.done();
        }
        return true;
      });
}

std::shared_ptr<Session> create_session(ServerContext& context, const json& body) {
  if (!body.is_object()) throw HttpError(400, "body", "expected a JSON object");
  for (const auto& item : body.items()) {
    if (item.key() != "scene") throw HttpError(400, item.key(), "unknown key (known: scene)");
  }
  auto session = context.sessions.create(context.session_context());
  try {
    run_job(context, session, false, [&] {
      if (body.contains("scene")) {
        session->set_scene(body["scene"]);
        return;
      }
      try {
        session->set_scene(json::parse(context.options.initial_scene.empty() ? default_initial_scene()
                                                                             : context.options.initial_scene));
      } catch (const std::exception& e) {
        // A configured initial scene that no longer loads (a file moved)
        // must not make the viewer unusable.
        fmt::print(stderr, "penumbra serve: initial scene failed ({}); using the builtin spheres\n", e.what());
        session->set_scene(json::parse(default_initial_scene()));
      }
    });
  } catch (...) {
    context.sessions.remove(session->id());
    throw;
  }
  return session;
}

}  // namespace

void add_routes(httplib::Server& http, ServerContext& context) {
  const int max_side = context.options.max_image_side;

  http.Get("/api/techniques", guarded([](const Request&, Response& res) { send_json(res, techniques_json()); }));

  http.Get("/api/volumes", guarded([&context](const Request&, Response& res) {
             send_json(res, volumes_json(context.data, context.options.max_builtin_size));
           }));

  http.Post("/api/presets", guarded([](const Request& req, Response& res) {
              const std::string name = req.has_param("name") ? req.get_param_value("name") : std::string();
              const TransferFunction tf = parse_paraview_preset(req.body, name, "preset");
              json points = json::array();
              for (const TransferFunctionPoint& p : tf.points()) {
                points.push_back({p.value, p.color.r, p.color.g, p.color.b, p.alpha});
              }
              send_json(res, {{"transfer_function", {{"points", points}, {"range", "data"}}}});
            }));

  http.Post("/api/sessions", guarded([&context](const Request& req, Response& res) {
              const auto session = create_session(context, parse_body(req, true));
              json body = scene_and_volume(*session);
              body["id"] = session->id();
              send_json(res, body, 201);
            }));

  http.Delete(kSessionPattern, guarded([&context](const Request& req, Response& res) {
                if (!context.sessions.remove(req.matches[1])) throw HttpError(404, "session", "unknown session");
                send_json(res, {{"deleted", std::string(req.matches[1])}});
              }));

  http.Get(std::string(kSessionPattern) + "/scene", guarded([&context](const Request& req, Response& res) {
             const auto session = context.sessions.find(req.matches[1]);
             res.set_header("Cache-Control", "no-store");
             res.set_content(session->scene_json(), "application/json");
           }));

  http.Put(std::string(kSessionPattern) + "/scene", guarded([&context](const Request& req, Response& res) {
             const auto session = context.sessions.find(req.matches[1]);
             const json scene = parse_body(req);
             run_job(context, session, false, [&] { session->set_scene(scene); });
             send_json(res, scene_and_volume(*session));
           }));

  http.Get(std::string(kSessionPattern) + "/volume", guarded([&context](const Request& req, Response& res) {
             send_json(res, context.sessions.find(req.matches[1])->volume_info());
           }));

  http.Post(std::string(kSessionPattern) + "/volume", guarded([&context](const Request& req, Response& res) {
              const auto session = context.sessions.find(req.matches[1]);
              const json volume = parse_body(req);
              run_job(context, session, false, [&] { session->load_volume(volume); });
              send_json(res, scene_and_volume(*session));
            }));

  http.Post(std::string(kSessionPattern) + "/frame", guarded([&context, max_side](const Request& req, Response& res) {
              const auto session = context.sessions.find(req.matches[1]);
              send_frame(res, render_frame(context, session, frame_request_from_json(parse_body(req), max_side)));
            }));

  http.Get(std::string(kSessionPattern) + "/frame", guarded([&context, max_side](const Request& req, Response& res) {
             const auto session = context.sessions.find(req.matches[1]);
             send_frame(res, render_frame(context, session, frame_request_from_query(req.params, max_side)));
           }));

  http.Get(std::string(kSessionPattern) + "/progressive",
           guarded([&context, max_side](const Request& req, Response& res) {
             const auto session = context.sessions.find(req.matches[1]);
             stream_progressive(context, session, frame_request_from_query(req.params, max_side), res);
           }));

  // The viewer's files: an exact lookup in the embedded table, so no request
  // path ever reaches the file system.
  http.Get("/[A-Za-z0-9_.-]*", [](const Request& req, Response& res) {
    const WebAsset* asset = find_web_asset(req.path);
    if (!asset) {
      send_error(res, 404, "", fmt::format("no such page: {}", req.path));
      return;
    }
    res.set_header("Cache-Control", "no-cache");
    res.set_content(asset->data, asset->size, std::string(content_type_for(asset->path)).c_str());
  });

  // Whatever matched no route, and errors httplib raises itself (a malformed
  // request line, a body over the size limit), still answer in JSON.
  http.set_error_handler(httplib::Server::HandlerWithResponse([](const Request& req, Response& res) {
    if (!res.body.empty()) return httplib::Server::HandlerResponse::Unhandled;
    const std::string message = res.status == 404   ? fmt::format("no such endpoint: {} {}", req.method, req.path)
                                : res.status == 413 ? std::string("request body too large")
                                                    : fmt::format("HTTP error {}", res.status);
    send_error(res, res.status, "", message);
    return httplib::Server::HandlerResponse::Handled;
  }));
  http.set_exception_handler([](const Request&, Response& res, std::exception_ptr error) {
    send_exception(res, error);
  });
}

}  // namespace penumbra::server

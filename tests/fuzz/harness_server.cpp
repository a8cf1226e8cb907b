// The server's request parsing as the handlers run it, with the fixture
// folder as the data folder: the first byte picks the request, the rest is
// its body or query string.
//   0: PUT /api/sessions/ID/scene   (body -> Session::set_scene)
//   1: POST /api/sessions/ID/frame  (body -> frame_request_from_json -> Session::render at <= 16x16)
//   2: GET /api/sessions/ID/frame?  (query -> frame_request_from_query -> Session::render at <= 16x16)
// Whatever is thrown goes through send_exception(), as in the handlers: a
// 4xx is the expected answer to a bad request, a 5xx is a finding.
#include "harness.h"

#include "penumbra/base/memory_budget.h"
#include "server/frame_request.h"
#include "server/http_responses.h"
#include "server/http_server.h"
#include "server/session.h"

#include <fmt/format.h>
#include <httplib.h>

namespace penumbra::server {
namespace {

using nlohmann::json;

constexpr int kMaxSide = 2048;  // ServerOptions' default

QueryParameters parse_query(std::string_view text) {
  QueryParameters query;
  std::size_t start = 0;
  while (start <= text.size()) {
    std::size_t end = text.find('&', start);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view pair = text.substr(start, end - start);
    const std::size_t eq = pair.find('=');
    query.emplace(httplib::detail::decode_url(std::string(pair.substr(0, eq)), true),
                  eq == std::string_view::npos ? std::string()
                                               : httplib::detail::decode_url(std::string(pair.substr(eq + 1)), true));
    start = end + 1;
  }
  return query;
}

void handle(Session& session, int mode, const std::string& text) {
  httplib::Request req;
  req.body = text;
  if (mode == 0) {
    session.set_scene(parse_body(req));
    return;
  }
  session.set_scene(json::parse(default_initial_scene()));
  FrameRequest request = mode == 1 ? frame_request_from_json(parse_body(req), kMaxSide)
                                   : frame_request_from_query(parse_query(text), kMaxSide);
  request.width = std::min(request.width, 16);
  request.height = std::min(request.height, 16);
  // At most 16 paths per pixel, as in fuzz_scene: more is work asked for, not a hang.
  if (request.scene && request.scene->is_object()) {
    json* params = nullptr;
    if (auto r = request.scene->find("render"); r != request.scene->end() && r->is_object()) {
      if (auto p = r->find("params"); p != r->end() && p->is_object()) params = &*p;
    }
    for (const char* name : {"spp", "min_spp"}) {
      if (params && params->contains(name) && (*params)[name].is_number() && (*params)[name].get<double>() > 16.0) {
        (*params)[name] = 16;
      }
    }
  }
  (void)session.render(request);
}

}  // namespace
}  // namespace penumbra::server

namespace penumbra::fuzz {

void fuzz_server(Input input) {
  using namespace penumbra::server;
  if (input.empty()) return;
  static const DataDirectory data(fixture_dir());
  static VolumeCache cache;
  set_memory_budget_bytes(std::uint64_t(64) << 20);
  Session session("fuzz", SessionContext{&data, &cache, SceneLimits{}});
  const std::string text(reinterpret_cast<const char*>(input.data()) + 1, input.size() - 1);
  try {
    handle(session, input[0] % 3, text);
  } catch (...) {
    httplib::Response res;
    send_exception(res, std::current_exception());
    if (res.status >= 500) {
      throw HarnessFailure(fmt::format("fuzz_server: a request got {}: {}", res.status, res.body));
    }
  }
}

}  // namespace penumbra::fuzz

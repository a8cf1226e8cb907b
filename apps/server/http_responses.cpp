#include "server/http_responses.h"

#include "penumbra/base/error.h"
#include "server/http_error.h"
#include "server/render_queue.h"

#include <fmt/format.h>

#include <new>

namespace penumbra::server {

using httplib::Request;
using httplib::Response;
using nlohmann::json;

void send_json(Response& res, const json& body, int status) {
  res.status = status;
  res.set_header("Cache-Control", "no-store");
  // Errors echo what clients sent (a query parameter's name, a key), which
  // need not be UTF-8: replace invalid bytes rather than throw from dump().
  res.set_content(body.dump(-1, ' ', false, json::error_handler_t::replace), "application/json");
}

void send_error(Response& res, int status, const std::string& key, const std::string& message) {
  json body{{"error", message}, {"status", status}};
  if (!key.empty()) body["key"] = key;
  send_json(res, body, status);
}

void send_exception(Response& res, const std::exception_ptr& error) {
  try {
    std::rethrow_exception(error);
  } catch (const HttpError& e) {
    send_error(res, e.status(), e.key(), e.what());
  } catch (const Superseded& e) {
    send_error(res, 409, "", e.what());
  } catch (const InvalidScene& e) {
    send_error(res, 400, e.key(), e.what());
  } catch (const InvalidArgument& e) {
    send_error(res, 400, e.name(), e.what());
  } catch (const OutOfMemoryBudget& e) {
    send_error(res, 413, "", e.what());
  } catch (const IoError& e) {
    send_error(res, 422, "", e.what());
  } catch (const json::exception& e) {
    send_error(res, 400, "", fmt::format("malformed JSON request: {}", e.what()));
  } catch (const std::bad_alloc&) {
    send_error(res, 503, "", "out of memory");
  } catch (const std::exception& e) {
    send_error(res, 500, "", fmt::format("internal error: {}", e.what()));
  } catch (...) {
    send_error(res, 500, "", "internal error");
  }
}

json parse_body(const Request& req, bool allow_empty) {
  if (req.body.empty()) {
    if (allow_empty) return json::object();
    throw HttpError(400, "body", "the request needs a JSON body");
  }
  try {
    return json::parse(req.body);
  } catch (const json::exception& e) {
    // parse_error, and out_of_range for a number beyond a double (1e400).
    throw HttpError(400, "body", fmt::format("not valid JSON: {}", e.what()));
  }
}

}  // namespace penumbra::server

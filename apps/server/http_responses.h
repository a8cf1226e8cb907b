#pragma once
// JSON answers and errors for the request handlers. Every error a client sees
// is {"error": message, "status": N} plus "key" (the request field it is
// about) when there is one; send_exception() picks the status by the
// exception's type, so handlers just throw.
#include <httplib.h>
#include <nlohmann/json.hpp>

#include <exception>
#include <string>

namespace penumbra::server {

void send_json(httplib::Response& res, const nlohmann::json& body, int status = 200);
void send_error(httplib::Response& res, int status, const std::string& key, const std::string& message);

// HttpError: its status. Superseded: 409. InvalidScene, InvalidArgument,
// malformed JSON: 400. OutOfMemoryBudget: 413. IoError (a file that cannot be
// read or a preset that does not parse): 422. Out of memory: 503. Anything
// else: 500.
void send_exception(httplib::Response& res, const std::exception_ptr& error);

// The request body as JSON; HttpError 400 ("body") when it is not JSON, or
// empty unless `allow_empty` (then an empty object).
nlohmann::json parse_body(const httplib::Request& req, bool allow_empty = false);

// Wraps a handler so that whatever it throws becomes a JSON error.
template <class F> httplib::Server::Handler guarded(F handler) {
  return [handler](const httplib::Request& req, httplib::Response& res) {
    try {
      handler(req, res);
    } catch (...) {
      send_exception(res, std::current_exception());
    }
  };
}

}  // namespace penumbra::server

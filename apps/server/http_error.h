#pragma once
// Errors that the server layer raises itself, with the HTTP status they map
// to. Engine errors (InvalidScene, IoError, ...) are mapped in routes.cpp;
// every error reaches the client as {"error": message, "key": key, "status": N}.
#include <stdexcept>
#include <string>

namespace penumbra::server {

class HttpError : public std::runtime_error {
 public:
  HttpError(int status, std::string key, const std::string& message)
      : std::runtime_error(message), status_(status), key_(std::move(key)) {}
  int status() const { return status_; }
  // The request field the error is about ("volume.file", "width"), or empty.
  const std::string& key() const { return key_; }

 private:
  int status_;
  std::string key_;
};

}  // namespace penumbra::server

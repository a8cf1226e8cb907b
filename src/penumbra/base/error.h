#pragma once
// Typed host-side errors. They are thrown with context by library code and
// caught only at the edges (CLI: exit code 2 and one line; server: 4xx + JSON).
// Kernels never throw.
#include <cstdint>
#include <stdexcept>
#include <string>

namespace penumbra {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A file that cannot be read, or whose content is malformed.
class IoError : public Error {
 public:
  IoError(std::string path, const std::string& what);
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// A scene (JSON or programmatic) with a missing, unknown or ill-typed key, or a
// value out of range. `key` is a dotted path such as "lights[1].direction".
class InvalidScene : public Error {
 public:
  InvalidScene(std::string key, const std::string& what);
  const std::string& key() const { return key_; }

 private:
  std::string key_;
};

// A bad technique parameter or command-line argument.
class InvalidArgument : public Error {
 public:
  InvalidArgument(std::string name, const std::string& what);
  const std::string& name() const { return name_; }

 private:
  std::string name_;
};

// An allocation that would exceed the memory budget (see memory_budget.h).
class OutOfMemoryBudget : public Error {
 public:
  OutOfMemoryBudget(const std::string& what, std::uint64_t bytes, std::uint64_t budget);
  std::uint64_t bytes() const { return bytes_; }

 private:
  std::uint64_t bytes_;
};

// A render stopped before it finished because its caller asked it to (see
// RenderProgress in render/technique.h): Ctrl-C in Python, a closed viewer.
class RenderCancelled : public Error {
 public:
  RenderCancelled() : Error("the render was cancelled") {}
};

}  // namespace penumbra

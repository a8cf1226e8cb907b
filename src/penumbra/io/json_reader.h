#pragma once
// Reading scene JSON objects strictly (io-internal): every key must be known,
// and conversion errors name the full key path ("lights[1].direction").
#include "penumbra/base/error.h"
#include "penumbra/base/math.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <initializer_list>
#include <string>

namespace penumbra::json_reader {

using nlohmann::json;

inline std::string type_name(const json& j) {
  if (j.is_number()) return "a number";
  if (j.is_string()) return "a string";
  if (j.is_boolean()) return "a boolean";
  if (j.is_array()) return "an array";
  if (j.is_object()) return "an object";
  return "null";
}

// One JSON object being read: checks that every key it holds is known and
// converts values with errors that name the full key path.
class ObjectReader {
 public:
  ObjectReader(const json& j, std::string path, std::initializer_list<const char*> known) : j_(j), path_(std::move(path)) {
    if (!j.is_object()) throw InvalidScene(path_.empty() ? "(root)" : path_, "expected an object, got " + type_name(j));
    for (const auto& item : j.items()) {
      bool ok = false;
      for (const char* k : known) ok = ok || item.key() == k;
      if (!ok) {
        std::string list;
        for (const char* k : known) list += fmt::format("{}{}", list.empty() ? "" : ", ", k);
        throw InvalidScene(key(item.key()), fmt::format("unknown key (known here: {})", list));
      }
    }
  }

  std::string key(const std::string& name) const { return path_.empty() ? name : path_ + "." + name; }
  bool has(const char* name) const { return j_.contains(name); }
  const json& at(const char* name) const { return j_.at(name); }

  float number(const char* name, float fallback) const {
    if (!has(name)) return fallback;
    return to_float(at(name), key(name));
  }
  int integer(const char* name, int fallback) const {
    if (!has(name)) return fallback;
    const json& v = at(name);
    if (!v.is_number_integer()) throw InvalidScene(key(name), "expected an integer, got " + type_name(v));
    const auto i = v.get<std::int64_t>();
    if (i < -(1 << 30) || i > (1 << 30)) throw InvalidScene(key(name), "integer out of range");
    return int(i);
  }
  bool boolean(const char* name, bool fallback) const {
    if (!has(name)) return fallback;
    const json& v = at(name);
    if (!v.is_boolean()) throw InvalidScene(key(name), "expected true or false, got " + type_name(v));
    return v.get<bool>();
  }
  std::string string(const char* name, const std::string& fallback) const {
    if (!has(name)) return fallback;
    const json& v = at(name);
    if (!v.is_string()) throw InvalidScene(key(name), "expected a string, got " + type_name(v));
    return v.get<std::string>();
  }
  vec3 vector3(const char* name, vec3 fallback) const {
    if (!has(name)) return fallback;
    return to_vec3(at(name), key(name));
  }

  static float to_float(const json& v, const std::string& key) {
    if (!v.is_number()) throw InvalidScene(key, "expected a number, got " + type_name(v));
    const double d = v.get<double>();
    if (!std::isfinite(d) || std::abs(d) > 3.0e38) throw InvalidScene(key, "number out of range");
    return float(d);
  }
  static vec3 to_vec3(const json& v, const std::string& key) {
    if (!v.is_array() || v.size() != 3) throw InvalidScene(key, "expected an array of 3 numbers");
    return vec3(to_float(v[0], key + "[0]"), to_float(v[1], key + "[1]"), to_float(v[2], key + "[2]"));
  }

 private:
  const json& j_;
  std::string path_;
};

inline json to_json(vec3 v) { return json::array({v.x, v.y, v.z}); }

// A file named in a scene, relative to the scene's folder unless absolute.
inline std::filesystem::path resolve(const std::filesystem::path& base_dir, const std::string& file) {
  const std::filesystem::path p(file);
  return p.is_absolute() ? p : base_dir / p;
}

}  // namespace penumbra::json_reader

#include "server/frame_request.h"

#include "server/http_error.h"

#include <fmt/format.h>

#include <charconv>

namespace penumbra::server {
namespace {

using nlohmann::json;

int integer_field(const json& value, const char* key, int lo, int hi) {
  if (!value.is_number_integer()) throw HttpError(400, key, "expected an integer");
  const auto v = value.get<std::int64_t>();
  if (v < lo || v > hi) throw HttpError(400, key, fmt::format("must be in [{}, {}], got {}", lo, hi, v));
  return int(v);
}

int integer_text(const std::string& text, const char* key, int lo, int hi) {
  int v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size()) throw HttpError(400, key, "expected an integer");
  if (v < lo || v > hi) throw HttpError(400, key, fmt::format("must be in [{}, {}], got {}", lo, hi, v));
  return v;
}

ImageFormat format_field(const std::string& name) {
  const auto format = image_format_from_string(name);
  if (!format) throw HttpError(400, "format", fmt::format("expected \"jpeg\" or \"png\", got \"{}\"", name));
  return *format;
}

}  // namespace

FrameRequest frame_request_from_json(const json& body, int max_side) {
  if (!body.is_object()) throw HttpError(400, "body", "expected a JSON object");
  FrameRequest r;
  for (const auto& item : body.items()) {
    const std::string& key = item.key();
    const json& v = item.value();
    if (key == "width") {
      r.width = integer_field(v, "width", 1, max_side);
    } else if (key == "height") {
      r.height = integer_field(v, "height", 1, max_side);
    } else if (key == "format") {
      if (!v.is_string()) throw HttpError(400, "format", "expected a string");
      r.format = format_field(v.get<std::string>());
    } else if (key == "quality") {
      r.quality = integer_field(v, "quality", 1, 100);
    } else if (key == "preview") {
      if (!v.is_boolean()) throw HttpError(400, "preview", "expected true or false");
      r.preview = v.get<bool>();
    } else if (key == "step_scale") {
      if (!v.is_number() || !(v.get<double>() >= 1.0 && v.get<double>() <= 16.0)) {
        throw HttpError(400, "step_scale", "expected a number in [1, 16]");
      }
      r.step_scale = v.get<float>();
    } else if (key == "scene") {
      r.scene = v;
    } else if (key == "camera") {
      if (!v.is_object()) throw HttpError(400, "camera", "expected a camera object (scene JSON v1)");
      r.camera = v;
    } else {
      throw HttpError(400, key, "unknown key (known: scene, camera, width, height, preview, step_scale, format, quality)");
    }
  }
  return r;
}

FrameRequest frame_request_from_query(const QueryParameters& query, int max_side) {
  FrameRequest r;
  for (const auto& [key, value] : query) {
    if (key == "width") {
      r.width = integer_text(value, "width", 1, max_side);
    } else if (key == "height") {
      r.height = integer_text(value, "height", 1, max_side);
    } else if (key == "format") {
      r.format = format_field(value);
    } else if (key == "quality") {
      r.quality = integer_text(value, "quality", 1, 100);
    } else if (key == "preview") {
      r.preview = value == "1" || value == "true";
    } else {
      throw HttpError(400, key, "unknown query parameter (known: width, height, format, quality, preview)");
    }
  }
  return r;
}

}  // namespace penumbra::server

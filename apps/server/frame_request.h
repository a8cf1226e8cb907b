#pragma once
// Frame requests as clients send them: a JSON body (POST .../frame) or a
// query string (GET .../frame, .../progressive). Strict: unknown keys and
// values out of range are HttpError 400 naming the field, checked before any
// work is queued.
#include "server/session.h"

#include <nlohmann/json.hpp>

#include <map>
#include <string>

namespace penumbra::server {

// {"scene"?, "camera"?, "width", "height", "preview"?, "step_scale"?, "format"?, "quality"?}
FrameRequest frame_request_from_json(const nlohmann::json& body, int max_side);

// width, height, format, quality, preview (httplib::Params is this multimap).
using QueryParameters = std::multimap<std::string, std::string>;
FrameRequest frame_request_from_query(const QueryParameters& query, int max_side);

}  // namespace penumbra::server

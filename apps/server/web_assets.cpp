#include "server/web_assets.h"

namespace penumbra::server {

const WebAsset* find_web_asset(std::string_view url_path) {
  if (url_path == "/") url_path = "/index.html";
  for (const WebAsset& asset : embedded_web_assets()) {
    if (asset.path == url_path) return &asset;
  }
  return nullptr;
}

std::string_view content_type_for(std::string_view path) {
  if (path.ends_with(".html")) return "text/html; charset=utf-8";
  if (path.ends_with(".js")) return "text/javascript; charset=utf-8";
  if (path.ends_with(".css")) return "text/css; charset=utf-8";
  return "application/octet-stream";
}

}  // namespace penumbra::server

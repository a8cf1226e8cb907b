#pragma once
// The browser viewer's files (apps/web), compiled into the binary by
// embed_files.cmake so that `penumbra serve` works from an installed binary.
#include <cstddef>
#include <string_view>
#include <vector>

namespace penumbra::server {

struct WebAsset {
  std::string_view path;  // "/index.html"
  const char* data;
  std::size_t size;
};

const std::vector<WebAsset>& embedded_web_assets();

// The asset served at a URL path ("/" is "/index.html"); nullptr if none.
const WebAsset* find_web_asset(std::string_view url_path);

// Content type by extension ("text/html; charset=utf-8", ...).
std::string_view content_type_for(std::string_view path);

}  // namespace penumbra::server

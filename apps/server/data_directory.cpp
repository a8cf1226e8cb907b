#include "server/data_directory.h"

#include "penumbra/io/text_parsing.h"
#include "penumbra/io/volume_reader.h"
#include "server/http_error.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>

namespace penumbra::server {
namespace fs = std::filesystem;

DataDirectory::DataDirectory(const fs::path& root) {
  if (root.empty()) return;
  std::error_code ec;
  root_ = fs::canonical(root, ec);
  if (ec || !fs::is_directory(root_, ec)) root_.clear();
}

bool DataDirectory::is_volume_file_name(std::string_view name) {
  const std::string lower = to_lower(name);
  for (const std::string& ext : supported_volume_extensions()) {
    if (lower.size() > ext.size() && lower.ends_with(ext)) return true;
  }
  return false;
}

bool DataDirectory::inside_root(const fs::path& real_path) const {
  auto root_it = root_.begin();
  auto path_it = real_path.begin();
  for (; root_it != root_.end(); ++root_it, ++path_it) {
    if (path_it == real_path.end() || *path_it != *root_it) return false;
  }
  return true;
}

fs::path DataDirectory::resolve_volume(std::string_view relative, const std::string& key) const {
  return resolve(relative, key, &DataDirectory::is_volume_file_name, "volume");
}

fs::path DataDirectory::resolve_mesh(std::string_view relative, const std::string& key) const {
  auto is_mesh = [](std::string_view name) {
    const std::string lower = to_lower(name);
    return lower.size() > 4 && (lower.ends_with(".obj") || lower.ends_with(".ply"));
  };
  return resolve(relative, key, +is_mesh, "mesh");
}

fs::path DataDirectory::resolve(std::string_view relative, const std::string& key, bool (*accept)(std::string_view),
                                const char* kind) const {
  if (!available()) throw HttpError(404, key, "the server has no data folder (start it with --data DIR)");
  if (relative.empty()) throw HttpError(400, key, "empty path");
  if (relative.size() > 1024) throw HttpError(400, key, "path too long");
  for (const char c : relative) {
    if (c == '\0' || c == '\\' || static_cast<unsigned char>(c) < 0x20) {
      throw HttpError(400, key, "path contains a control character or a backslash");
    }
  }
  const fs::path path(relative);
  if (path.is_absolute() || relative.front() == '/') {
    throw HttpError(400, key, "absolute paths are not allowed: name a file relative to the data folder");
  }
  for (const fs::path& part : path) {
    if (part == "..") throw HttpError(400, key, "\"..\" is not allowed in a path");
  }
  std::error_code ec;
  const fs::path real = fs::weakly_canonical(root_ / path, ec);
  if (ec || !inside_root(real)) throw HttpError(403, key, fmt::format("'{}' lies outside the data folder", relative));
  if (!fs::exists(real, ec)) throw HttpError(404, key, fmt::format("'{}': no such file in the data folder", relative));
  if (!fs::is_regular_file(real, ec)) throw HttpError(400, key, fmt::format("'{}' is not a file", relative));
  if (!accept(real.filename().string()) || !accept(path.filename().string())) {
    throw HttpError(415, key, fmt::format("'{}' is not a supported {} file", relative, kind));
  }
  return real;
}

std::string DataDirectory::relative_message(std::string_view message) const {
  std::string out(message);
  if (!available()) return out;
  const std::string prefix = (root_ / "").string();  // with the trailing '/'
  for (std::size_t at = out.find(prefix); at != std::string::npos; at = out.find(prefix, at)) out.erase(at, prefix.size());
  // The root itself, where a message names the folder.
  for (std::size_t at = out.find(root_.string()); at != std::string::npos; at = out.find(root_.string(), at)) {
    out.replace(at, root_.string().size(), "the data folder");
  }
  return out;
}

std::vector<DataEntry> DataDirectory::list_volumes(int max_depth) const {
  std::vector<DataEntry> entries;
  if (!available()) return entries;
  std::error_code ec;
  fs::recursive_directory_iterator it(root_, fs::directory_options::skip_permission_denied, ec);
  for (; !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
    if (it.depth() >= max_depth) it.disable_recursion_pending();
    const fs::path& p = it->path();
    if (!is_volume_file_name(p.filename().string())) continue;
    std::error_code file_ec;
    const fs::path real = fs::canonical(p, file_ec);
    if (file_ec || !inside_root(real) || !fs::is_regular_file(real, file_ec)) continue;
    entries.push_back({p.lexically_relative(root_).generic_string(), fs::file_size(real, file_ec)});
  }
  std::sort(entries.begin(), entries.end(), [](const DataEntry& a, const DataEntry& b) { return a.path < b.path; });
  return entries;
}

}  // namespace penumbra::server

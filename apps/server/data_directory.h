#pragma once
// The folder of volumes the server may read (`penumbra serve --data DIR`).
// Clients name volumes by paths relative to it; nothing outside it is ever
// opened: absolute paths and ".." components are refused outright, and a
// path whose real location (symlinks resolved) leaves the folder is refused
// as well, so a symlink inside the folder cannot be used to escape it.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace penumbra::server {

struct DataEntry {
  std::string path;  // relative to the root, '/'-separated
  std::uint64_t bytes = 0;
};

class DataDirectory {
 public:
  // An empty root means "no data folder": the listing is empty and every
  // path is refused.
  explicit DataDirectory(const std::filesystem::path& root);

  bool available() const { return !root_.empty(); }
  const std::filesystem::path& root() const { return root_; }

  // The real path of the volume file `relative` names. Throws HttpError:
  // 400 for a malformed or absolute path or one with "..", 403 for a path
  // that resolves outside the root, 404 for a missing file, 415 for a file
  // that is not a supported volume format. `key` names the request field.
  std::filesystem::path resolve_volume(std::string_view relative, const std::string& key) const;
  // The same for a mesh file (.obj or .ply; 415 for anything else).
  std::filesystem::path resolve_mesh(std::string_view relative, const std::string& key) const;

  // Every supported volume file under the root (at most `max_depth` folders
  // deep), sorted by path; files whose real location is outside the root are
  // left out.
  std::vector<DataEntry> list_volumes(int max_depth = 4) const;

  // `message` with every mention of the root folder dropped, so that paths
  // in it read relative to the data folder ("CT/head.nhdr: truncated").
  std::string relative_message(std::string_view message) const;

  // Whether `name` ends in one of the readers' extensions (case-insensitive).
  static bool is_volume_file_name(std::string_view name);

 private:
  bool inside_root(const std::filesystem::path& real_path) const;
  // The checks both resolve_* share; `accept` says whether a file name has the right kind.
  std::filesystem::path resolve(std::string_view relative, const std::string& key, bool (*accept)(std::string_view),
                                const char* kind) const;

  std::filesystem::path root_;  // canonical
};

}  // namespace penumbra::server

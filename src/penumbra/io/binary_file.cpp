#include "penumbra/io/binary_file.h"

#include "penumbra/base/error.h"
#include "penumbra/base/memory_budget.h"

#include <fmt/format.h>

#include <fstream>
#include <system_error>

namespace penumbra {

std::string display_path(const std::filesystem::path& path) { return path.string(); }

std::uint64_t file_size_checked(const std::filesystem::path& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) throw IoError(display_path(path), "file not found");
  if (!std::filesystem::is_regular_file(status)) throw IoError(display_path(path), "not a regular file");
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) throw IoError(display_path(path), fmt::format("cannot read the file size: {}", ec.message()));
  return static_cast<std::uint64_t>(size);
}

std::vector<std::byte> read_whole_file(const std::filesystem::path& path) {
  const std::uint64_t size = file_size_checked(path);
  check_memory_budget(fmt::format("reading {}", display_path(path)), size);
  std::vector<std::byte> bytes(static_cast<std::size_t>(size));
  read_file_range(path, 0, bytes, "file content");
  return bytes;
}

std::string read_text_file(const std::filesystem::path& path) {
  const std::vector<std::byte> bytes = read_whole_file(path);
  return std::string(reinterpret_cast<const char*>(bytes.data()), bytes.size());
}

void read_file_range(const std::filesystem::path& path, std::uint64_t offset, std::span<std::byte> out,
                     const std::string& what) {
  const std::uint64_t size = file_size_checked(path);
  if (offset > size || out.size() > size - offset) {
    throw IoError(display_path(path),
                  fmt::format("{} is truncated: needs {} bytes at offset {}, but the file has {} bytes", what,
                              out.size(), offset, size));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(display_path(path), "cannot open the file for reading");
  in.seekg(static_cast<std::streamoff>(offset));
  in.read(reinterpret_cast<char*>(out.data()), static_cast<std::streamsize>(out.size()));
  if (static_cast<std::uint64_t>(in.gcount()) != out.size()) {
    throw IoError(display_path(path), fmt::format("{} is truncated: read {} of {} bytes", what, in.gcount(),
                                                  out.size()));
  }
}

void write_whole_file(const std::filesystem::path& path, std::span<const std::byte> bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw IoError(display_path(path), "cannot open the file for writing");
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  out.flush();
  if (!out) throw IoError(display_path(path), "write failed (disk full?)");
}

}  // namespace penumbra

#include "penumbra/io/text_header.h"

#include "penumbra/base/error.h"
#include "penumbra/io/binary_file.h"

#include <fmt/format.h>

#include <fstream>

namespace penumbra {

TextHeader read_text_header(const std::filesystem::path& path,
                            const std::function<bool(std::string_view line)>& ends_after, std::uint64_t max_bytes) {
  const std::uint64_t size = file_size_checked(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(display_path(path), "cannot open the file for reading");

  TextHeader header;
  std::string pending;  // bytes of the current, unfinished line
  std::uint64_t consumed = 0;
  char buffer[64 * 1024];
  while (consumed < size) {
    in.read(buffer, sizeof buffer);
    const auto got = static_cast<std::size_t>(in.gcount());
    if (got == 0) break;
    for (std::size_t i = 0; i < got; ++i) {
      ++consumed;
      if (buffer[i] != '\n') {
        pending.push_back(buffer[i]);
        if (pending.size() > max_bytes) {
          throw IoError(display_path(path), fmt::format("header line longer than {} bytes; not a text header", max_bytes));
        }
        continue;
      }
      if (!pending.empty() && pending.back() == '\r') pending.pop_back();
      header.lines.push_back(std::move(pending));
      pending.clear();
      if (ends_after(header.lines.back())) {
        header.data_offset = consumed;
        return header;
      }
      if (consumed > max_bytes) {
        throw IoError(display_path(path), fmt::format("header is longer than {} bytes", max_bytes));
      }
    }
  }
  if (!pending.empty()) {
    if (pending.back() == '\r') pending.pop_back();
    header.lines.push_back(std::move(pending));
    if (ends_after(header.lines.back())) {
      header.data_offset = consumed;
      return header;
    }
  }
  header.data_offset = consumed;
  header.reached_end_of_file = true;
  return header;
}

}  // namespace penumbra

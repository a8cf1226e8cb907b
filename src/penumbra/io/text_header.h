#pragma once
// The text header at the start of a file (NRRD, MetaImage, .dat), read line
// by line up to where the header ends, so an attached header's voxels are
// never read as text and their offset is exact.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace penumbra {

struct TextHeader {
  std::vector<std::string> lines;  // without the line terminators
  std::uint64_t data_offset = 0;   // first byte after the header
  bool reached_end_of_file = false;
};

// Reads lines until `ends_after(line)` returns true for a line (that line is
// kept and the data start after it) or the file ends. IoError if the header
// would be longer than max_bytes (which protects against reading a binary
// file as one endless line).
TextHeader read_text_header(const std::filesystem::path& path,
                            const std::function<bool(std::string_view line)>& ends_after,
                            std::uint64_t max_bytes = 16u << 20);

}  // namespace penumbra

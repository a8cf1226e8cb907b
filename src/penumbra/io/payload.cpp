#include "penumbra/io/payload.h"

#include "penumbra/base/error.h"
#include "penumbra/io/binary_file.h"
#include "penumbra/io/compression.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <fstream>

namespace penumbra {
namespace {

constexpr std::uint64_t kChunk = 4u << 20;

std::uint64_t raw_start(const PayloadSource& source, std::uint64_t file_size, std::uint64_t bytes) {
  if (source.at_end) return file_size >= bytes ? file_size - bytes : 0;
  return source.offset;
}

}  // namespace

void check_payload_size(const PayloadSource& source, std::uint64_t bytes, const std::string& what) {
  const std::uint64_t file_size = file_size_checked(source.file);
  if (source.encoding == PayloadEncoding::Raw) {
    const std::uint64_t start = raw_start(source, file_size, bytes);
    if (start > file_size || bytes > file_size - start) {
      throw IoError(display_path(source.file),
                    fmt::format("{} is truncated: needs {} bytes from offset {}, but the file has only {} bytes there",
                                what, bytes, start, start > file_size ? 0 : file_size - start));
    }
    return;
  }
  if (source.offset > file_size) {
    throw IoError(display_path(source.file), fmt::format("{} should start at byte {}, but the file has {} bytes",
                                                         what, source.offset, file_size));
  }
  std::uint64_t compressed = file_size - source.offset;
  if (source.compressed_size > 0) compressed = std::min(compressed, source.compressed_size);
  const std::uint64_t needed = bytes + source.skip_after_decoding;
  if (needed > max_inflated_size(compressed)) {
    throw IoError(display_path(source.file),
                  fmt::format("{} needs {} bytes, more than {} compressed bytes can hold; the header's sizes are "
                              "wrong or the file is truncated",
                              what, needed, compressed));
  }
}

void read_payload(const PayloadSource& source, std::uint64_t bytes, VolumeByteCursor& cursor,
                  const std::string& what) {
  if (source.encoding == PayloadEncoding::Raw) {
    check_payload_size(source, bytes, what);
    const std::uint64_t file_size = file_size_checked(source.file);
    std::ifstream in(source.file, std::ios::binary);
    if (!in) throw IoError(display_path(source.file), "cannot open the file for reading");
    in.seekg(static_cast<std::streamoff>(raw_start(source, file_size, bytes)));
    while (bytes > 0) {
      const std::span<std::byte> piece = cursor.next(std::min(bytes, kChunk));
      if (piece.empty()) break;
      in.read(reinterpret_cast<char*>(piece.data()), static_cast<std::streamsize>(piece.size()));
      if (static_cast<std::size_t>(in.gcount()) != piece.size()) {
        throw IoError(display_path(source.file), fmt::format("{} is truncated: the file ended early", what));
      }
      bytes -= piece.size();
    }
    return;
  }
  InflateStream stream(source.file, source.offset);
  stream.skip(source.skip_after_decoding, what);
  while (bytes > 0) {
    const std::span<std::byte> piece = cursor.next(std::min(bytes, kChunk));
    if (piece.empty()) break;
    stream.read_exact(piece, what);
    bytes -= piece.size();
  }
}

std::uint64_t offset_after_lines(const std::filesystem::path& file, std::uint64_t start, std::uint64_t lines) {
  if (lines == 0) return start;
  const std::uint64_t size = file_size_checked(file);
  std::ifstream in(file, std::ios::binary);
  if (!in) throw IoError(display_path(file), "cannot open the file for reading");
  in.seekg(static_cast<std::streamoff>(start));
  std::array<char, 64 * 1024> buffer;
  std::uint64_t position = start;
  std::uint64_t found = 0;
  while (position < size) {
    in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    const auto got = static_cast<std::size_t>(in.gcount());
    if (got == 0) break;
    for (std::size_t i = 0; i < got; ++i) {
      if (buffer[i] == '\n' && ++found == lines) return position + i + 1;
    }
    position += got;
  }
  throw IoError(display_path(file),
                fmt::format("'line skip' asks to skip {} lines, but the file has only {}", lines, found));
}

}  // namespace penumbra

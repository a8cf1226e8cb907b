#pragma once
// zlib/gzip streams for voxel payloads. Inflation is pull-based and only ever
// produces the bytes the caller asks for, so a small file that would expand
// to terabytes (a "zip bomb") costs nothing: the reader asks for exactly the
// voxel bytes its header promised, and those were checked against the memory
// budget first.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace penumbra {

enum class CompressionFormat { Zlib, Gzip };

// Deflate cannot compress better than about 1032:1, so a compressed payload
// of `compressed_bytes` cannot hold more than this many bytes. Readers use it
// to reject absurd headers before allocating.
std::uint64_t max_inflated_size(std::uint64_t compressed_bytes);

// Decompresses a zlib or gzip stream (detected from its header; concatenated
// gzip members are read as one stream) from a file range or from memory.
class InflateStream {
 public:
  // The stream starts at `offset` in the file; `source` names it in errors.
  InflateStream(const std::filesystem::path& path, std::uint64_t offset);
  // The stream is `compressed` (which must outlive this object).
  InflateStream(std::span<const std::byte> compressed, std::string source);
  ~InflateStream();
  InflateStream(const InflateStream&) = delete;
  InflateStream& operator=(const InflateStream&) = delete;

  // Fills `out` completely or throws IoError saying that `what` is truncated
  // or that the compressed data is corrupt.
  void read_exact(std::span<std::byte> out, const std::string& what);
  // Discards `bytes` bytes of decompressed data.
  void skip(std::uint64_t bytes, const std::string& what);
  // Bytes produced so far.
  std::uint64_t position() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

using ByteSink = std::function<void(std::span<const std::byte>)>;

// Streaming compressor: write() any number of times, then finish() once.
class Deflater {
 public:
  explicit Deflater(CompressionFormat format, int level = 6);
  ~Deflater();
  Deflater(const Deflater&) = delete;
  Deflater& operator=(const Deflater&) = delete;

  void write(std::span<const std::byte> data, const ByteSink& sink);
  void finish(const ByteSink& sink);

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// One-shot helpers (the output buffer is checked against the memory budget).
std::vector<std::byte> deflate_bytes(std::span<const std::byte> data, CompressionFormat format, int level = 6);

}  // namespace penumbra

#include "penumbra/io/compression.h"

#include "penumbra/base/error.h"
#include "penumbra/base/memory_budget.h"
#include "penumbra/io/binary_file.h"

#include <fmt/format.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <fstream>
#include <limits>

namespace penumbra {

std::uint64_t max_inflated_size(std::uint64_t compressed_bytes) {
  // 1032:1 is deflate's limit (a 258-byte match coded in 2 bits, roughly);
  // the constant covers the headers of tiny streams.
  return checked_product({compressed_bytes, 1032}) + 4096;
}

namespace {

constexpr std::size_t kInputChunk = 1 << 20;
// zlib counts in uInt; feed it at most this much at a time.
constexpr std::size_t kMaxZlibChunk = std::numeric_limits<uInt>::max() / 2;

}  // namespace

struct InflateStream::State {
  std::string source;
  // Exactly one of these provides the input.
  std::ifstream file;
  std::uint64_t file_remaining = 0;
  std::span<const std::byte> memory;
  std::vector<unsigned char> buffer;

  z_stream z{};
  bool initialised = false;
  bool finished = false;
  std::uint64_t produced = 0;

  // Hands zlib more input; false when there is none left.
  bool refill() {
    if (!memory.empty()) {
      const std::size_t n = std::min(memory.size(), kMaxZlibChunk);
      z.next_in = reinterpret_cast<Bytef*>(const_cast<std::byte*>(memory.data()));
      z.avail_in = static_cast<uInt>(n);
      memory = memory.subspan(n);
      return true;
    }
    if (file_remaining == 0) return false;
    const std::size_t n = static_cast<std::size_t>(std::min<std::uint64_t>(file_remaining, kInputChunk));
    buffer.resize(n);
    file.read(reinterpret_cast<char*>(buffer.data()), static_cast<std::streamsize>(n));
    const auto got = static_cast<std::size_t>(file.gcount());
    if (got == 0) return false;
    file_remaining -= got;
    z.next_in = buffer.data();
    z.avail_in = static_cast<uInt>(got);
    return true;
  }

  void init() {
    // 15 + 32: accept both zlib and gzip headers.
    if (inflateInit2(&z, 15 + 32) != Z_OK) throw IoError(source, "cannot initialise zlib");
    initialised = true;
  }

  // Fills up to out.size() bytes; returns the count (less only at the end of
  // the compressed stream).
  std::size_t read_some(std::span<std::byte> out) {
    std::size_t done = 0;
    while (done < out.size() && !finished) {
      if (z.avail_in == 0 && !refill()) break;
      const std::size_t want = std::min(out.size() - done, kMaxZlibChunk);
      z.next_out = reinterpret_cast<Bytef*>(out.data() + done);
      z.avail_out = static_cast<uInt>(want);
      const int rc = inflate(&z, Z_NO_FLUSH);
      const std::size_t got = want - z.avail_out;
      done += got;
      produced += got;
      if (rc == Z_STREAM_END) {
        // gzip allows several members back to back (what `cat a.gz b.gz`
        // makes); continue when another member follows.
        if (z.avail_in == 0) refill();
        if (z.avail_in >= 2 && z.next_in[0] == 0x1f && z.next_in[1] == 0x8b) {
          inflateReset(&z);
        } else {
          finished = true;
        }
      } else if (rc == Z_NEED_DICT || rc == Z_DATA_ERROR) {
        throw IoError(source, fmt::format("corrupt compressed data after {} bytes: {}", produced,
                                          z.msg ? z.msg : "invalid deflate stream"));
      } else if (rc == Z_MEM_ERROR) {
        throw IoError(source, "zlib ran out of memory");
      } else if (rc == Z_BUF_ERROR) {
        // No progress possible: either the input ran out inside the stream
        // (truncated; the caller reports it) or zlib is stuck.
        if (z.avail_in > 0 || !refill()) break;
      }
    }
    return done;
  }
};

InflateStream::InflateStream(const std::filesystem::path& path, std::uint64_t offset)
    : state_(std::make_unique<State>()) {
  state_->source = display_path(path);
  const std::uint64_t size = file_size_checked(path);
  if (offset > size) {
    throw IoError(state_->source, fmt::format("compressed data should start at byte {}, but the file has {} bytes",
                                              offset, size));
  }
  state_->file.open(path, std::ios::binary);
  if (!state_->file) throw IoError(state_->source, "cannot open the file for reading");
  state_->file.seekg(static_cast<std::streamoff>(offset));
  state_->file_remaining = size - offset;
  state_->init();
}

InflateStream::InflateStream(std::span<const std::byte> compressed, std::string source)
    : state_(std::make_unique<State>()) {
  state_->source = std::move(source);
  state_->memory = compressed;
  state_->init();
}

InflateStream::~InflateStream() {
  if (state_ && state_->initialised) inflateEnd(&state_->z);
}

void InflateStream::read_exact(std::span<std::byte> out, const std::string& what) {
  const std::uint64_t before = state_->produced;
  const std::size_t got = state_->read_some(out);
  if (got != out.size()) {
    throw IoError(state_->source,
                  fmt::format("{} is truncated: the compressed stream ends after {} bytes, {} more were expected", what,
                              before + got, out.size() - got));
  }
}

void InflateStream::skip(std::uint64_t bytes, const std::string& what) {
  std::array<std::byte, 64 * 1024> scratch;
  while (bytes > 0) {
    const std::size_t n = static_cast<std::size_t>(std::min<std::uint64_t>(bytes, scratch.size()));
    read_exact(std::span(scratch.data(), n), what);
    bytes -= n;
  }
}

std::uint64_t InflateStream::position() const { return state_->produced; }

struct Deflater::State {
  z_stream z{};
  std::array<unsigned char, 256 * 1024> out;

  void pump(int flush, const ByteSink& sink) {
    int rc = Z_OK;
    do {
      z.next_out = out.data();
      z.avail_out = static_cast<uInt>(out.size());
      rc = deflate(&z, flush);
      if (rc == Z_STREAM_ERROR) throw Error("zlib deflate failed");
      const std::size_t produced = out.size() - z.avail_out;
      if (produced > 0) sink(std::span(reinterpret_cast<const std::byte*>(out.data()), produced));
    } while (z.avail_out == 0 || (flush == Z_FINISH && rc != Z_STREAM_END));
  }
};

Deflater::Deflater(CompressionFormat format, int level) : state_(std::make_unique<State>()) {
  // 15 + 16 writes a gzip header instead of a zlib one.
  const int window_bits = format == CompressionFormat::Gzip ? 15 + 16 : 15;
  if (deflateInit2(&state_->z, level, Z_DEFLATED, window_bits, 8, Z_DEFAULT_STRATEGY) != Z_OK) {
    throw Error("cannot initialise zlib deflate");
  }
}

Deflater::~Deflater() { deflateEnd(&state_->z); }

void Deflater::write(std::span<const std::byte> data, const ByteSink& sink) {
  while (!data.empty()) {
    const std::size_t n = std::min(data.size(), kMaxZlibChunk);
    state_->z.next_in = reinterpret_cast<Bytef*>(const_cast<std::byte*>(data.data()));
    state_->z.avail_in = static_cast<uInt>(n);
    state_->pump(Z_NO_FLUSH, sink);
    data = data.subspan(n);
  }
}

void Deflater::finish(const ByteSink& sink) {
  state_->z.next_in = nullptr;
  state_->z.avail_in = 0;
  state_->pump(Z_FINISH, sink);
}

std::vector<std::byte> deflate_bytes(std::span<const std::byte> data, CompressionFormat format, int level) {
  check_memory_budget("a compression buffer", compressBound(static_cast<uLong>(data.size())));
  std::vector<std::byte> result;
  result.reserve(data.size() / 2 + 64);
  const ByteSink append = [&](std::span<const std::byte> piece) { result.insert(result.end(), piece.begin(), piece.end()); };
  Deflater deflater(format, level);
  deflater.write(data, append);
  deflater.finish(append);
  return result;
}

}  // namespace penumbra

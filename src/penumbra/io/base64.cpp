#include "penumbra/io/base64.h"

#include <fmt/format.h>

#include <array>

namespace penumbra {
namespace {

constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

constexpr std::array<int, 256> make_table() {
  std::array<int, 256> table{};
  for (int& v : table) v = -1;
  for (int i = 0; i < 64; ++i) table[static_cast<unsigned char>(kAlphabet[i])] = i;
  return table;
}
constexpr std::array<int, 256> kTable = make_table();

bool is_space(char c) { return c == ' ' || c == '\n' || c == '\r' || c == '\t'; }

}  // namespace

std::string base64_encode(std::span<const std::byte> data) {
  std::string out;
  out.reserve((data.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 3 <= data.size(); i += 3) {
    const unsigned v = unsigned(data[i]) << 16 | unsigned(data[i + 1]) << 8 | unsigned(data[i + 2]);
    out += kAlphabet[v >> 18 & 63];
    out += kAlphabet[v >> 12 & 63];
    out += kAlphabet[v >> 6 & 63];
    out += kAlphabet[v & 63];
  }
  if (i < data.size()) {
    const bool two = i + 1 < data.size();
    const unsigned v = unsigned(data[i]) << 16 | (two ? unsigned(data[i + 1]) << 8 : 0u);
    out += kAlphabet[v >> 18 & 63];
    out += kAlphabet[v >> 12 & 63];
    out += two ? kAlphabet[v >> 6 & 63] : '=';
    out += '=';
  }
  return out;
}

bool Base64Decoder::decode_group() {
  int values[4];
  int count = 0;
  int padding = 0;
  while (count < 4 && position_ < text_.size()) {
    const char c = text_[position_++];
    if (is_space(c)) continue;
    if (c == '=') {
      if (count < 2) {
        error_ = fmt::format("misplaced '=' at character {}", position_ - 1);
        return false;
      }
      ++padding;
      values[count++] = 0;
      continue;
    }
    const int v = kTable[static_cast<unsigned char>(c)];
    if (v < 0 || padding > 0) {
      error_ = fmt::format("invalid base64 character '{}' at character {}", c, position_ - 1);
      return false;
    }
    values[count++] = v;
  }
  if (count < 2) {
    error_ = "base64 data ended early";
    return false;
  }
  // A final group without its padding decodes as if it were padded.
  if (count < 4) padding = 4 - count;
  const unsigned v = unsigned(values[0]) << 18 | unsigned(values[1]) << 12 | unsigned(count > 2 ? values[2] : 0) << 6 |
                     unsigned(count > 3 ? values[3] : 0);
  pending_[0] = std::byte(v >> 16 & 255);
  pending_[1] = std::byte(v >> 8 & 255);
  pending_[2] = std::byte(v & 255);
  pending_count_ = 3 - padding;
  pending_next_ = 0;
  return true;
}

bool Base64Decoder::read_exact(std::span<std::byte> out) {
  std::size_t done = 0;
  while (done < out.size()) {
    if (pending_count_ == 0 && !decode_group()) return false;
    while (pending_count_ > 0 && done < out.size()) {
      out[done++] = pending_[pending_next_++];
      --pending_count_;
    }
  }
  return true;
}

}  // namespace penumbra

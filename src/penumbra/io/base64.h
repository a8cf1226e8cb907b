#pragma once
// Base64 (RFC 4648) for VTK XML files. VTK writes the header of a binary
// DataArray and its data as separately padded base64 streams back to back, so
// the decoder works group by group and accepts padding in the middle; it
// skips whitespace and refuses any other character.
#include <cstddef>
#include <span>
#include <string>
#include <string_view>

namespace penumbra {

std::string base64_encode(std::span<const std::byte> data);

class Base64Decoder {
 public:
  explicit Base64Decoder(std::string_view text) : text_(text) {}

  // Fills `out` completely and returns true, or returns false (see error())
  // on an invalid character or when the text ends first.
  bool read_exact(std::span<std::byte> out);
  const std::string& error() const { return error_; }
  // Upper bound of the bytes left to decode.
  std::size_t remaining_bound() const { return (text_.size() - position_) / 4 * 3 + 3 + pending_count_; }

 private:
  bool decode_group();

  std::string_view text_;
  std::size_t position_ = 0;
  std::byte pending_[3]{};
  int pending_count_ = 0;
  int pending_next_ = 0;
  std::string error_;
};

}  // namespace penumbra

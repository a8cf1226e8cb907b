#include "penumbra/io/xml_scanner.h"

#include "penumbra/base/error.h"

#include <fmt/format.h>

#include <cstdint>

namespace penumbra {
namespace {

bool is_space(char c) { return c == ' ' || c == '\n' || c == '\r' || c == '\t'; }

bool is_name_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == ':' ||
         c == '-' || c == '.' || static_cast<unsigned char>(c) >= 0x80;
}

void append_utf8(std::string& out, std::uint32_t code) {
  if (code < 0x80) {
    out += static_cast<char>(code);
  } else if (code < 0x800) {
    out += static_cast<char>(0xC0 | (code >> 6));
    out += static_cast<char>(0x80 | (code & 0x3F));
  } else if (code < 0x10000) {
    out += static_cast<char>(0xE0 | (code >> 12));
    out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (code & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (code >> 18));
    out += static_cast<char>(0x80 | ((code >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (code & 0x3F));
  }
}

}  // namespace

const std::string* XmlTag::attribute(std::string_view wanted) const {
  for (const auto& [key, value] : attributes) {
    if (key == wanted) return &value;
  }
  return nullptr;
}

std::string xml_unescape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '&') {
      out += text[i];
      continue;
    }
    const std::size_t semicolon = text.find(';', i);
    if (semicolon == std::string_view::npos || semicolon - i > 12) {
      out += text[i];
      continue;
    }
    const std::string_view entity = text.substr(i + 1, semicolon - i - 1);
    if (entity == "lt") {
      out += '<';
    } else if (entity == "gt") {
      out += '>';
    } else if (entity == "amp") {
      out += '&';
    } else if (entity == "quot") {
      out += '"';
    } else if (entity == "apos") {
      out += '\'';
    } else if (entity.size() > 1 && entity[0] == '#') {
      const bool hex = entity[1] == 'x' || entity[1] == 'X';
      std::uint32_t code = 0;
      bool valid = entity.size() > (hex ? 2u : 1u);
      for (char c : entity.substr(hex ? 2 : 1)) {
        int digit = -1;
        if (c >= '0' && c <= '9') digit = c - '0';
        if (hex && c >= 'a' && c <= 'f') digit = c - 'a' + 10;
        if (hex && c >= 'A' && c <= 'F') digit = c - 'A' + 10;
        if (digit < 0 || code > 0x10FFFF) {
          valid = false;
          break;
        }
        code = code * (hex ? 16u : 10u) + static_cast<std::uint32_t>(digit);
      }
      if (!valid || code > 0x10FFFF) {
        out += text.substr(i, semicolon - i + 1);
      } else {
        append_utf8(out, code);
      }
    } else {
      out += text.substr(i, semicolon - i + 1);  // unknown entity: keep as written
    }
    i = semicolon;
  }
  return out;
}

void XmlScanner::fail(const std::string& what) const {
  throw IoError(source_, fmt::format("malformed XML at byte {}: {}", position_, what));
}

void XmlScanner::skip_spaces() {
  while (position_ < text_.size() && is_space(text_[position_])) ++position_;
}

std::string XmlScanner::read_name() {
  const std::size_t start = position_;
  while (position_ < text_.size() && is_name_char(text_[position_])) ++position_;
  if (position_ == start) fail("expected a name");
  return std::string(text_.substr(start, position_ - start));
}

std::optional<XmlTag> XmlScanner::next() {
  while (true) {
    const std::size_t open = text_.find('<', position_);
    if (open == std::string_view::npos) {
      position_ = text_.size();
      return std::nullopt;
    }
    position_ = open;
    const std::string_view rest = text_.substr(open);
    // Markup that is not a tag: skip to its terminator.
    const auto skip_past = [&](std::string_view terminator, const char* what) {
      const std::size_t close = text_.find(terminator, open);
      if (close == std::string_view::npos) fail(fmt::format("unterminated {}", what));
      position_ = close + terminator.size();
    };
    if (rest.starts_with("<!--")) {
      skip_past("-->", "comment");
      continue;
    }
    if (rest.starts_with("<?")) {
      skip_past("?>", "processing instruction");
      continue;
    }
    if (rest.starts_with("<![CDATA[")) {
      skip_past("]]>", "CDATA section");
      continue;
    }
    if (rest.starts_with("<!")) {
      skip_past(">", "declaration");
      continue;
    }

    XmlTag tag;
    tag.begin = open;
    ++position_;
    if (position_ < text_.size() && text_[position_] == '/') {
      tag.kind = XmlTag::Kind::End;
      ++position_;
    }
    tag.name = read_name();
    while (true) {
      skip_spaces();
      if (position_ >= text_.size()) fail(fmt::format("unterminated tag <{}>", tag.name));
      const char c = text_[position_];
      if (c == '>') {
        ++position_;
        break;
      }
      if (c == '/' && tag.kind == XmlTag::Kind::Start && position_ + 1 < text_.size() &&
          text_[position_ + 1] == '>') {
        tag.kind = XmlTag::Kind::SelfClosing;
        position_ += 2;
        break;
      }
      if (tag.kind == XmlTag::Kind::End) fail(fmt::format("unexpected '{}' in </{}>", c, tag.name));
      std::string key = read_name();
      skip_spaces();
      if (position_ >= text_.size() || text_[position_] != '=') {
        fail(fmt::format("attribute '{}' of <{}> has no value", key, tag.name));
      }
      ++position_;
      skip_spaces();
      if (position_ >= text_.size() || (text_[position_] != '"' && text_[position_] != '\'')) {
        fail(fmt::format("attribute '{}' of <{}> is not quoted", key, tag.name));
      }
      const char quote = text_[position_++];
      const std::size_t close = text_.find(quote, position_);
      if (close == std::string_view::npos) fail(fmt::format("attribute '{}' of <{}> is not closed", key, tag.name));
      tag.attributes.emplace_back(std::move(key), xml_unescape(text_.substr(position_, close - position_)));
      position_ = close + 1;
    }
    tag.end = position_;
    return tag;
  }
}

}  // namespace penumbra

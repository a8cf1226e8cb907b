#pragma once
// A small pull scanner for the XML that volume formats and presets use (VTK
// XML, ParaView colour maps): it returns tags with their attributes in order
// and skips text, comments, processing instructions, CDATA and DOCTYPE. It
// does not build a tree or validate nesting, so the caller can stop at a tag
// (VTK's <AppendedData> is followed by raw binary that is not XML) and read
// the bytes between tags itself.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace penumbra {

struct XmlTag {
  enum class Kind { Start, End, SelfClosing };
  Kind kind = Kind::Start;
  std::string name;
  std::vector<std::pair<std::string, std::string>> attributes;  // values unescaped
  std::size_t begin = 0;  // offset of '<'
  std::size_t end = 0;    // offset just past '>'

  const std::string* attribute(std::string_view name) const;
};

class XmlScanner {
 public:
  // `source` names the document in IoError messages.
  XmlScanner(std::string_view text, std::string source) : text_(text), source_(std::move(source)) {}

  // The next tag, or nullopt at the end of the text. Throws IoError for
  // malformed markup.
  std::optional<XmlTag> next();
  std::size_t position() const { return position_; }

 private:
  [[noreturn]] void fail(const std::string& what) const;
  std::string read_name();
  void skip_spaces();

  std::string_view text_;
  std::string source_;
  std::size_t position_ = 0;
};

// Replaces the five predefined entities and numeric character references.
std::string xml_unescape(std::string_view text);

}  // namespace penumbra

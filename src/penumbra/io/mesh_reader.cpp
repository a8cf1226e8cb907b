// OBJ and PLY mesh readers (see mesh_reader.h for what each accepts).
#include "penumbra/io/mesh_reader.h"

#include "penumbra/base/error.h"
#include "penumbra/base/memory_budget.h"
#include "penumbra/base/numeric_cast.h"
#include "penumbra/io/binary_file.h"
#include "penumbra/io/byte_order.h"
#include "penumbra/io/text_parsing.h"

#include <fmt/format.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace penumbra {
namespace {

// A position read as doubles, as floats; a coordinate beyond the float range
// (1e300, whose cast would be undefined) becomes NaN, which the callers refuse.
vec3 float_position(const std::array<double, 3>& xyz) {
  vec3 p;
  for (int a = 0; a < 3; ++a) p[a] = to_float(xyz[std::size_t(a)]).value_or(std::numeric_limits<float>::quiet_NaN());
  return p;
}

constexpr std::uint64_t kMaxVertices = std::numeric_limits<std::uint32_t>::max();  // glm::uvec3 indices

bool finite(const vec3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

void add_fan(std::vector<glm::uvec3>& triangles, std::span<const std::uint32_t> corners) {
  for (std::size_t k = 1; k + 1 < corners.size(); ++k) triangles.emplace_back(corners[0], corners[k], corners[k + 1]);
}

// ---------------------------------------------------------------- OBJ

class ObjParser {
 public:
  explicit ObjParser(const std::filesystem::path& path) : path_(path) {}

  TriangleMesh parse(std::string_view text) {
    const std::vector<std::string_view> lines = split_lines(text);
    std::string joined;  // a statement continued over lines with a trailing '\'
    std::size_t first_line = 0;
    for (std::size_t n = 0; n < lines.size(); ++n) {
      std::string_view line = lines[n];
      if (joined.empty()) first_line = n + 1;
      if (!line.empty() && line.back() == '\\') {
        line.remove_suffix(1);
        joined.append(line).push_back(' ');
        continue;
      }
      if (!joined.empty()) {
        joined.append(line);
        statement(joined, first_line);
        joined.clear();
      } else {
        statement(line, first_line);
      }
    }
    if (!joined.empty()) statement(joined, first_line);

    if (has_index_ && max_index_ >= mesh_.positions.size()) {
      fail(max_index_line_, fmt::format("vertex index {} is out of range: the file has {} vertices", max_index_ + 1,
                                        mesh_.positions.size()));
    }
    if (mesh_.triangles.empty()) throw IoError(display_path(path_), "OBJ file has no faces");
    return std::move(mesh_);
  }

 private:
  [[noreturn]] void fail(std::size_t line, const std::string& what) const {
    throw IoError(display_path(path_), fmt::format("OBJ line {}: {}", line, what));
  }

  void statement(std::string_view line, std::size_t n) {
    if (const std::size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    const std::vector<std::string_view> words = split_words(line);
    if (words.empty()) return;
    if (words[0] == "v") {
      vertex(words, n);
    } else if (words[0] == "f") {
      face(words, n);
    }
    // vt, vn, vp, g, o, s, usemtl, mtllib, l, p and unknown statements carry
    // nothing a closed volume needs.
  }

  void vertex(const std::vector<std::string_view>& words, std::size_t n) {
    // x y z, then optionally w, or a colour r g b (MeshLab), or both.
    if (words.size() < 4 || words.size() > 8) {
      fail(n, fmt::format("a vertex needs 3 coordinates (v x y z [w]), found {} values", words.size() - 1));
    }
    std::array<double, 3> xyz{};
    for (std::size_t k = 1; k < words.size(); ++k) {
      const std::optional<double> value = parse_double(words[k]);
      if (!value) fail(n, fmt::format("vertex value '{}' is not a number", words[k]));
      if (k <= 3) xyz[k - 1] = *value;
    }
    const vec3 p = float_position(xyz);
    if (!finite(p)) fail(n, "vertex position is not finite (or beyond the float range)");
    if (mesh_.positions.size() >= kMaxVertices) fail(n, "more than 2^32 - 1 vertices");
    mesh_.positions.push_back(p);
  }

  void face(const std::vector<std::string_view>& words, std::size_t n) {
    if (words.size() < 4) fail(n, fmt::format("a face needs at least 3 vertices, found {}", words.size() - 1));
    corners_.clear();
    for (std::size_t k = 1; k < words.size(); ++k) corners_.push_back(corner(words[k], n));
    add_fan(mesh_.triangles, corners_);
  }

  // "i", "i/t", "i//n" or "i/t/n"; returns the 0-based vertex index.
  std::uint32_t corner(std::string_view token, std::size_t n) {
    std::array<std::string_view, 3> parts{};
    std::size_t count = 0;
    for (std::string_view rest = token;;) {
      if (count == 3) fail(n, fmt::format("face corner '{}' has more than 3 parts", token));
      const std::size_t slash = rest.find('/');
      parts[count++] = rest.substr(0, slash);
      if (slash == std::string_view::npos) break;
      rest.remove_prefix(slash + 1);
    }
    for (std::size_t k = 1; k < count; ++k) {
      if (!parts[k].empty() && !parse_int(parts[k])) fail(n, fmt::format("face corner '{}' is malformed", token));
    }
    const std::optional<std::int64_t> index = parse_int(parts[0]);
    if (!index) fail(n, fmt::format("face corner '{}' has no vertex index", token));
    const auto count_so_far = static_cast<std::int64_t>(mesh_.positions.size());
    if (*index == 0) fail(n, "vertex index 0 (OBJ indices start at 1)");
    if (*index < 0) {
      if (-*index > count_so_far) {
        fail(n, fmt::format("relative vertex index {} reaches before the first vertex ({} so far)", *index,
                            count_so_far));
      }
      return static_cast<std::uint32_t>(count_so_far + *index);
    }
    if (static_cast<std::uint64_t>(*index) > kMaxVertices) {
      fail(n, fmt::format("vertex index {} is out of range", *index));
    }
    // Positive indices may refer to vertices defined later; checked at the end.
    const auto zero_based = static_cast<std::uint64_t>(*index - 1);
    if (!has_index_ || zero_based > max_index_) {
      max_index_ = zero_based;
      max_index_line_ = n;
      has_index_ = true;
    }
    return static_cast<std::uint32_t>(zero_based);
  }

  const std::filesystem::path& path_;
  TriangleMesh mesh_;
  std::vector<std::uint32_t> corners_;
  bool has_index_ = false;
  std::uint64_t max_index_ = 0;
  std::size_t max_index_line_ = 0;
};

// ---------------------------------------------------------------- PLY

enum class PlyType : std::uint8_t { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

std::optional<PlyType> ply_type(std::string_view name) {
  struct Entry {
    std::string_view name;
    PlyType type;
  };
  static constexpr Entry kTypes[] = {
      {"char", PlyType::Int8},     {"int8", PlyType::Int8},       {"uchar", PlyType::UInt8},
      {"uint8", PlyType::UInt8},   {"short", PlyType::Int16},     {"int16", PlyType::Int16},
      {"ushort", PlyType::UInt16}, {"uint16", PlyType::UInt16},   {"int", PlyType::Int32},
      {"int32", PlyType::Int32},   {"uint", PlyType::UInt32},     {"uint32", PlyType::UInt32},
      {"float", PlyType::Float32}, {"float32", PlyType::Float32}, {"double", PlyType::Float64},
      {"float64", PlyType::Float64},
  };
  for (const Entry& entry : kTypes) {
    if (entry.name == name) return entry.type;
  }
  return std::nullopt;
}

std::size_t type_size(PlyType type) {
  switch (type) {
    case PlyType::Int8:
    case PlyType::UInt8: return 1;
    case PlyType::Int16:
    case PlyType::UInt16: return 2;
    case PlyType::Int32:
    case PlyType::UInt32:
    case PlyType::Float32: return 4;
    case PlyType::Float64: return 8;
  }
  return 0;
}

bool is_integer(PlyType type) { return type != PlyType::Float32 && type != PlyType::Float64; }

enum class PlyFormat : std::uint8_t { Ascii, BinaryLittleEndian, BinaryBigEndian };

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::Float32;  // the item type for lists
  bool is_list = false;
  PlyType count_type = PlyType::UInt8;
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;

  bool has_lists() const {
    for (const PlyProperty& p : properties) {
      if (p.is_list) return true;
    }
    return false;
  }
  // Bytes of one element in a binary file, counting empty lists.
  std::uint64_t min_binary_size() const {
    std::uint64_t size = 0;
    for (const PlyProperty& p : properties) size += type_size(p.is_list ? p.count_type : p.type);
    return size;
  }
  int find(std::string_view property) const {
    for (std::size_t i = 0; i < properties.size(); ++i) {
      if (properties[i].name == property) return static_cast<int>(i);
    }
    return -1;
  }
};

struct PlyHeader {
  PlyFormat format = PlyFormat::Ascii;
  std::vector<PlyElement> elements;
  std::size_t body_offset = 0;
};

PlyHeader parse_ply_header(const std::filesystem::path& path, std::string_view bytes) {
  const auto fail = [&](std::size_t line, const std::string& what) {
    throw IoError(display_path(path), fmt::format("PLY header line {}: {}", line, what));
  };
  PlyHeader header;
  bool has_format = false;
  std::size_t pos = 0;
  for (std::size_t n = 1;; ++n) {
    const std::size_t newline = bytes.find('\n', pos);
    if (newline == std::string_view::npos) {
      if (n == 1) throw IoError(display_path(path), "not a PLY file (the first line is not 'ply')");
      throw IoError(display_path(path), "PLY header has no 'end_header' line");
    }
    std::string_view line = bytes.substr(pos, newline - pos);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    pos = newline + 1;
    if (n == 1) {
      if (trim(line) != "ply") throw IoError(display_path(path), "not a PLY file (the first line is not 'ply')");
      continue;
    }
    const std::vector<std::string_view> words = split_words(line);
    if (words.empty()) continue;
    const std::string_view keyword = words[0];
    if (keyword == "comment" || keyword == "obj_info") continue;
    if (keyword == "end_header") {
      if (!has_format) fail(n, "'end_header' before a 'format' line");
      header.body_offset = pos;
      return header;
    }
    if (keyword == "format") {
      if (words.size() != 3) fail(n, "expected 'format <ascii|binary_little_endian|binary_big_endian> 1.0'");
      if (words[1] == "ascii") {
        header.format = PlyFormat::Ascii;
      } else if (words[1] == "binary_little_endian") {
        header.format = PlyFormat::BinaryLittleEndian;
      } else if (words[1] == "binary_big_endian") {
        header.format = PlyFormat::BinaryBigEndian;
      } else {
        fail(n, fmt::format("unknown format '{}'", words[1]));
      }
      has_format = true;
    } else if (keyword == "element") {
      if (words.size() != 3) fail(n, "expected 'element <name> <count>'");
      const std::optional<std::int64_t> count = parse_int(words[2]);
      if (!count || *count < 0) fail(n, fmt::format("element count '{}' is not a non-negative integer", words[2]));
      header.elements.push_back(PlyElement{std::string(words[1]), static_cast<std::uint64_t>(*count), {}});
    } else if (keyword == "property") {
      if (header.elements.empty()) fail(n, "'property' before any 'element'");
      PlyProperty property;
      if (words.size() >= 2 && words[1] == "list") {
        if (words.size() != 5) fail(n, "expected 'property list <count type> <item type> <name>'");
        const auto count_type = ply_type(words[2]);
        const auto item_type = ply_type(words[3]);
        if (!count_type) fail(n, fmt::format("unknown type '{}'", words[2]));
        if (!item_type) fail(n, fmt::format("unknown type '{}'", words[3]));
        if (!is_integer(*count_type)) fail(n, fmt::format("list count type '{}' is not an integer type", words[2]));
        property = PlyProperty{std::string(words[4]), *item_type, true, *count_type};
      } else {
        if (words.size() != 3) fail(n, "expected 'property <type> <name>'");
        const auto type = ply_type(words[1]);
        if (!type) fail(n, fmt::format("unknown type '{}'", words[1]));
        property = PlyProperty{std::string(words[2]), *type, false, PlyType::UInt8};
      }
      header.elements.back().properties.push_back(std::move(property));
    } else {
      fail(n, fmt::format("unknown keyword '{}'", keyword));
    }
  }
}

// Values of a binary body, converted from the file's byte order.
class BinaryBody {
 public:
  BinaryBody(std::string_view bytes, std::endian order) : bytes_(bytes), order_(order) {}

  std::optional<double> read(PlyType type) {
    const std::size_t size = type_size(type);
    if (bytes_.size() - pos_ < size) return std::nullopt;
    std::array<std::byte, 8> raw{};
    std::memcpy(raw.data(), bytes_.data() + pos_, size);
    convert_byte_order(std::span(raw.data(), size), size, order_);
    pos_ += size;
    switch (type) {
      case PlyType::Int8: return as<std::int8_t>(raw);
      case PlyType::UInt8: return as<std::uint8_t>(raw);
      case PlyType::Int16: return as<std::int16_t>(raw);
      case PlyType::UInt16: return as<std::uint16_t>(raw);
      case PlyType::Int32: return as<std::int32_t>(raw);
      case PlyType::UInt32: return as<std::uint32_t>(raw);
      case PlyType::Float32: return as<float>(raw);
      case PlyType::Float64: return as<double>(raw);
    }
    return std::nullopt;
  }
  // Skips `count` values of `type`; false at the end of the file.
  bool skip(PlyType type, std::uint64_t count) {
    const std::uint64_t size = checked_product({count, type_size(type)});
    if (bytes_.size() - pos_ < size) return false;
    pos_ += static_cast<std::size_t>(size);
    return true;
  }
  // Skips whole elements without lists.
  bool skip_elements(const PlyElement& element) {
    return skip(PlyType::UInt8, checked_product({element.count, element.min_binary_size()}));
  }
  std::string_view problem() const { return "the file ends inside it"; }

 private:
  template <class T> static double as(const std::array<std::byte, 8>& raw) {
    T value;
    std::memcpy(&value, raw.data(), sizeof(T));
    return static_cast<double>(value);
  }

  std::string_view bytes_;
  std::size_t pos_ = 0;
  std::endian order_;
};

// Whitespace-separated values of an ascii body. Line breaks are not
// significant, as in most readers.
class AsciiBody {
 public:
  explicit AsciiBody(std::string_view text) : text_(text) {}

  std::optional<double> read(PlyType type) {
    const std::string_view token = next();
    if (token.empty()) {
      problem_ = "the file ends inside it";
      return std::nullopt;
    }
    if (is_integer(type)) {
      const std::optional<std::int64_t> value = parse_int(token);
      if (!value) {
        problem_ = fmt::format("'{}' is not an integer", token);
        return std::nullopt;
      }
      return static_cast<double>(*value);
    }
    const std::optional<double> value = parse_double(token);
    if (!value) {
      problem_ = fmt::format("'{}' is not a number", token);
      return std::nullopt;
    }
    return *value;
  }
  bool skip(PlyType, std::uint64_t count) {
    for (std::uint64_t i = 0; i < count; ++i) {
      if (next().empty()) {
        problem_ = "the file ends inside it";
        return false;
      }
    }
    return true;
  }
  bool skip_elements(const PlyElement& element) {
    return skip(PlyType::UInt8, checked_product({element.count, element.properties.size()}));
  }
  std::string_view problem() const { return problem_; }

 private:
  static bool space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f'; }
  std::string_view next() {
    while (pos_ < text_.size() && space(text_[pos_])) ++pos_;
    const std::size_t start = pos_;
    while (pos_ < text_.size() && !space(text_[pos_])) ++pos_;
    return text_.substr(start, pos_ - start);
  }

  std::string_view text_;
  std::size_t pos_ = 0;
  std::string problem_;
};

class PlyParser {
 public:
  PlyParser(const std::filesystem::path& path, const PlyHeader& header) : path_(path), header_(header) {}

  template <class Body> TriangleMesh parse(Body& body, std::uint64_t body_size) {
    check_counts(body_size);
    find_properties();
    const PlyElement& vertices = header_.elements[vertex_element_];
    check_memory_budget(fmt::format("mesh vertices of {}", display_path(path_)),
                        checked_product({vertices.count, sizeof(vec3)}));
    check_memory_budget(fmt::format("mesh faces of {}", display_path(path_)),
                        checked_product({header_.elements[face_element_].count, sizeof(glm::uvec3)}));
    mesh_.positions.reserve(static_cast<std::size_t>(vertices.count));
    mesh_.triangles.reserve(static_cast<std::size_t>(header_.elements[face_element_].count));

    for (std::size_t e = 0; e < header_.elements.size(); ++e) {
      const PlyElement& element = header_.elements[e];
      if (element.properties.empty() || element.count == 0) continue;
      if (e != vertex_element_ && e != face_element_ && !element.has_lists()) {
        if (!body.skip_elements(element)) {
          throw IoError(display_path(path_), fmt::format("PLY element '{}': the file ends inside it", element.name));
        }
        continue;
      }
      for (std::uint64_t i = 0; i < element.count; ++i) read_element(body, e, i);
    }
    if (mesh_.triangles.empty()) throw IoError(display_path(path_), "PLY file has no faces");
    return std::move(mesh_);
  }

 private:
  [[noreturn]] void fail(const PlyElement& element, std::uint64_t index, const PlyProperty& property,
                         std::string_view what) const {
    throw IoError(display_path(path_),
                  fmt::format("PLY element '{}' {}, property '{}': {}", element.name, index, property.name, what));
  }

  // A file that is too short for its declared counts is rejected here, before
  // any allocation sized by them.
  void check_counts(std::uint64_t body_size) const {
    std::uint64_t needed = 0;
    for (const PlyElement& element : header_.elements) {
      // Binary: every value has its size (lists at least their count). Ascii:
      // every value is a token of at least one character plus a separator.
      const std::uint64_t per_element = header_.format == PlyFormat::Ascii ? 2 * element.properties.size()
                                                                           : element.min_binary_size();
      const std::uint64_t bytes = checked_product({element.count, per_element});
      needed = bytes > std::numeric_limits<std::uint64_t>::max() - needed ? bytes : needed + bytes;
      // The last ascii value needs no separator after it.
      const std::uint64_t available = header_.format == PlyFormat::Ascii ? body_size + 1 : body_size;
      if (needed > available) {
        throw IoError(display_path(path_),
                      fmt::format("PLY header declares {} '{}' elements, but the file is too short for them "
                                  "({} bytes after the header)",
                                  element.count, element.name, body_size));
      }
    }
  }

  void find_properties() {
    const auto find_element = [&](std::string_view name) -> std::size_t {
      std::size_t found = kNone;
      for (std::size_t e = 0; e < header_.elements.size(); ++e) {
        if (header_.elements[e].name != name) continue;
        if (found != kNone) throw IoError(display_path(path_), fmt::format("PLY has two '{}' elements", name));
        found = e;
      }
      if (found == kNone) throw IoError(display_path(path_), fmt::format("PLY has no '{}' element", name));
      return found;
    };
    vertex_element_ = find_element("vertex");
    face_element_ = find_element("face");
    const PlyElement& vertex = header_.elements[vertex_element_];
    if (vertex.count > kMaxVertices) {
      throw IoError(display_path(path_), fmt::format("PLY 'vertex' count {} exceeds 2^32 - 1", vertex.count));
    }
    for (int axis = 0; axis < 3; ++axis) {
      const char* names[] = {"x", "y", "z"};
      const int index = vertex.find(names[axis]);
      if (index < 0 || vertex.properties[static_cast<std::size_t>(index)].is_list) {
        throw IoError(display_path(path_), fmt::format("PLY 'vertex' element has no scalar '{}' property",
                                                       names[axis]));
      }
      xyz_[axis] = index;
    }
    const PlyElement& face = header_.elements[face_element_];
    indices_ = face.find("vertex_indices");
    if (indices_ < 0) indices_ = face.find("vertex_index");
    if (indices_ < 0 || !face.properties[static_cast<std::size_t>(indices_)].is_list) {
      throw IoError(display_path(path_), "PLY 'face' element has no 'vertex_indices' list property");
    }
    if (!is_integer(face.properties[static_cast<std::size_t>(indices_)].type)) {
      throw IoError(display_path(path_), "PLY 'face' vertex indices are not of an integer type");
    }
  }

  template <class Body> void read_element(Body& body, std::size_t e, std::uint64_t i) {
    const PlyElement& element = header_.elements[e];
    std::array<double, 3> xyz{};
    for (std::size_t p = 0; p < element.properties.size(); ++p) {
      const PlyProperty& property = element.properties[p];
      if (!property.is_list) {
        const std::optional<double> value = body.read(property.type);
        if (!value) fail(element, i, property, body.problem());
        if (e == vertex_element_) {
          for (int axis = 0; axis < 3; ++axis) {
            if (xyz_[axis] == static_cast<int>(p)) xyz[axis] = *value;
          }
        }
        continue;
      }
      const std::optional<double> count = body.read(property.count_type);
      if (!count) fail(element, i, property, body.problem());
      if (*count < 0) {
        fail(element, i, property, fmt::format("negative list length {}", static_cast<std::int64_t>(*count)));
      }
      const auto length = static_cast<std::uint64_t>(*count);
      if (e != face_element_ || static_cast<int>(p) != indices_) {
        if (!body.skip(property.type, length)) fail(element, i, property, body.problem());
        continue;
      }
      if (length < 3) fail(element, i, property, fmt::format("a face needs at least 3 vertices, found {}", length));
      corners_.clear();
      for (std::uint64_t k = 0; k < length; ++k) {
        const std::optional<double> index = body.read(property.type);
        if (!index) fail(element, i, property, body.problem());
        const std::uint64_t vertex_count = header_.elements[vertex_element_].count;
        if (*index < 0 || *index >= static_cast<double>(vertex_count)) {
          fail(element, i, property,
               fmt::format("vertex index {} is out of range: the file has {} vertices",
                           static_cast<std::int64_t>(*index), vertex_count));
        }
        corners_.push_back(static_cast<std::uint32_t>(*index));
      }
      add_fan(mesh_.triangles, corners_);
    }
    if (e == vertex_element_) {
      const vec3 position = float_position(xyz);
      if (!finite(position)) {
        throw IoError(display_path(path_),
                      fmt::format("PLY element 'vertex' {}: position is not finite (or beyond the float range)", i));
      }
      mesh_.positions.push_back(position);
    }
  }

  static constexpr std::size_t kNone = static_cast<std::size_t>(-1);
  const std::filesystem::path& path_;
  const PlyHeader& header_;
  std::size_t vertex_element_ = kNone;
  std::size_t face_element_ = kNone;
  std::array<int, 3> xyz_{-1, -1, -1};
  int indices_ = -1;
  TriangleMesh mesh_;
  std::vector<std::uint32_t> corners_;
};

}  // namespace

TriangleMesh read_obj(const std::filesystem::path& path) {
  const std::string text = read_text_file(path);
  return ObjParser(path).parse(text);
}

TriangleMesh read_ply(const std::filesystem::path& path) {
  const std::string bytes = read_text_file(path);
  const PlyHeader header = parse_ply_header(path, bytes);
  const std::string_view body = std::string_view(bytes).substr(header.body_offset);
  PlyParser parser(path, header);
  if (header.format == PlyFormat::Ascii) {
    AsciiBody reader(body);
    return parser.parse(reader, body.size());
  }
  BinaryBody reader(body, header.format == PlyFormat::BinaryLittleEndian ? std::endian::little : std::endian::big);
  return parser.parse(reader, body.size());
}

TriangleMesh read_mesh(const std::filesystem::path& path) {
  const std::string extension = to_lower(path.extension().string());
  if (extension == ".obj") return read_obj(path);
  if (extension == ".ply") return read_ply(path);
  throw IoError(display_path(path),
                fmt::format("unknown mesh format '{}': expected a .obj or .ply file", path.extension().string()));
}

}  // namespace penumbra

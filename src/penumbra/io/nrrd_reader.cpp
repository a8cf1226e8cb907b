#include "penumbra/io/nrrd_reader.h"

#include "penumbra/base/error.h"
#include "penumbra/base/memory_budget.h"
#include "penumbra/base/numeric_cast.h"
#include "penumbra/io/binary_file.h"
#include "penumbra/io/file_pattern.h"
#include "penumbra/io/text_header.h"
#include "penumbra/io/text_parsing.h"
#include "penumbra/io/volume_layout.h"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace penumbra {
namespace {

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& what) {
  throw IoError(display_path(path), "NRRD header: " + what);
}

// NRRD's type names, with the C spellings it accepts, collapsed to single
// spaces and lower case.
std::optional<VoxelType> nrrd_type(std::string_view name) {
  static const std::map<std::string, VoxelType, std::less<>> kTypes = {
      {"signed char", VoxelType::Int8},         {"int8", VoxelType::Int8},
      {"int8_t", VoxelType::Int8},              {"uchar", VoxelType::UInt8},
      {"unsigned char", VoxelType::UInt8},      {"uint8", VoxelType::UInt8},
      {"uint8_t", VoxelType::UInt8},            {"short", VoxelType::Int16},
      {"short int", VoxelType::Int16},          {"signed short", VoxelType::Int16},
      {"signed short int", VoxelType::Int16},   {"int16", VoxelType::Int16},
      {"int16_t", VoxelType::Int16},            {"ushort", VoxelType::UInt16},
      {"unsigned short", VoxelType::UInt16},    {"unsigned short int", VoxelType::UInt16},
      {"uint16", VoxelType::UInt16},            {"uint16_t", VoxelType::UInt16},
      {"int", VoxelType::Int32},                {"signed int", VoxelType::Int32},
      {"int32", VoxelType::Int32},              {"int32_t", VoxelType::Int32},
      {"uint", VoxelType::UInt32},              {"unsigned int", VoxelType::UInt32},
      {"uint32", VoxelType::UInt32},            {"uint32_t", VoxelType::UInt32},
      {"float", VoxelType::Float32},            {"double", VoxelType::Float64},
  };
  std::string key;
  for (std::string_view word : split_words(name)) {
    if (!key.empty()) key += ' ';
    key += to_lower(word);
  }
  const auto it = kTypes.find(key);
  if (it == kTypes.end()) return std::nullopt;
  return it->second;
}

// A NRRD vector "(1,0,0)" or the word "none" (axes that are not spatial).
using OptionalVector = std::optional<std::vector<double>>;

std::vector<OptionalVector> parse_vectors(const std::filesystem::path& path, std::string_view field,
                                          std::string_view text) {
  std::vector<OptionalVector> vectors;
  std::size_t i = 0;
  while (i < text.size()) {
    if (text[i] == ' ' || text[i] == '\t') {
      ++i;
    } else if (text[i] == '(') {
      const std::size_t close = text.find(')', i);
      if (close == std::string_view::npos) fail(path, fmt::format("'{}' has a '(' without ')'", field));
      const auto components = parse_doubles(text.substr(i + 1, close - i - 1), ",");
      if (!components || components->empty()) {
        fail(path, fmt::format("'{}' has a vector that is not a list of numbers: '{}'", field,
                               text.substr(i, close - i + 1)));
      }
      vectors.emplace_back(*components);
      i = close + 1;
    } else if (equals_ignore_case(text.substr(i, 4), "none")) {
      vectors.emplace_back(std::nullopt);
      i += 4;
    } else {
      fail(path, fmt::format("'{}' should be vectors like (1,0,0) or 'none', got '{}'", field, text));
    }
  }
  return vectors;
}

struct NrrdHeader {
  std::map<std::string, std::string, std::less<>> fields;
  std::vector<std::string> listed_files;  // "data file: LIST" lines
  std::uint64_t data_offset = 0;          // attached data start here
};

NrrdHeader parse_header(const std::filesystem::path& path) {
  bool first = true;
  bool listing = false;
  NrrdHeader header;
  // A blank line ends the header; detached headers may just end.
  const TextHeader text = read_text_header(path, [&](std::string_view line) {
    if (first) {
      first = false;
      return false;
    }
    return trim(line).empty();
  });
  if (text.lines.empty() || text.lines.front().rfind("NRRD", 0) != 0) {
    throw IoError(display_path(path), "not a NRRD file: it does not start with the magic 'NRRD000X'");
  }
  header.data_offset = text.data_offset;
  for (std::size_t n = 1; n < text.lines.size(); ++n) {
    const std::string_view line = text.lines[n];
    if (trim(line).empty()) break;
    if (listing) {
      header.listed_files.emplace_back(trim(line));
      continue;
    }
    if (line.front() == '#') continue;
    if (line.find(":=") != std::string_view::npos) continue;  // key/value pairs carry no layout
    // "field: value", or "field:" with an empty value.
    std::size_t colon = line.find(": ");
    if (colon == std::string_view::npos && line.back() == ':') colon = line.size() - 1;
    if (colon == std::string_view::npos) {
      fail(path, fmt::format("line {} is neither 'field: value' nor a comment: '{}'", n + 1, line));
    }
    const std::string field = to_lower(trim(line.substr(0, colon)));
    const std::string value(colon + 2 <= line.size() ? trim(line.substr(colon + 2)) : std::string_view());
    if (header.fields.count(field)) fail(path, fmt::format("field '{}' appears twice", field));
    header.fields.emplace(field, value);
    if (field == "data file" || field == "datafile") {
      const auto words = split_words(value);
      listing = !words.empty() && words.front() == "LIST";
    }
  }
  return header;
}

const std::string* find_field(const NrrdHeader& header, std::initializer_list<std::string_view> names) {
  for (std::string_view name : names) {
    const auto it = header.fields.find(name);
    if (it != header.fields.end()) return &it->second;
  }
  return nullptr;
}

std::int64_t int_field(const std::filesystem::path& path, const NrrdHeader& header, std::string_view name,
                       std::int64_t fallback) {
  const std::string* value = find_field(header, {name});
  if (!value) return fallback;
  const auto parsed = parse_int(*value);
  if (!parsed) fail(path, fmt::format("'{}' should be an integer, got '{}'", name, *value));
  return *parsed;
}

std::filesystem::path resolve_data_file(const std::filesystem::path& header_path, std::string_view name) {
  const std::filesystem::path file(std::string(trim(name)));
  if (file.is_absolute()) return file;
  return header_path.parent_path() / file;
}

}  // namespace

std::shared_ptr<Volume> read_nrrd(const std::filesystem::path& path) {
  const NrrdHeader header = parse_header(path);

  // dimension and sizes
  const std::string* dimension_text = find_field(header, {"dimension"});
  if (!dimension_text) fail(path, "the required field 'dimension' is missing");
  const auto dimension = parse_int(*dimension_text);
  if (!dimension) fail(path, fmt::format("'dimension' should be an integer, got '{}'", *dimension_text));
  if (*dimension != 3 && *dimension != 4) {
    fail(path, fmt::format("'dimension' is {}; penumbra reads 3D volumes and 4D time series", *dimension));
  }
  const std::string* sizes_text = find_field(header, {"sizes"});
  if (!sizes_text) fail(path, "the required field 'sizes' is missing");
  const auto sizes = parse_ints(*sizes_text);
  if (!sizes) fail(path, fmt::format("'sizes' should be integers, got '{}'", *sizes_text));
  if (static_cast<std::int64_t>(sizes->size()) != *dimension) {
    fail(path, fmt::format("'sizes' has {} entries but 'dimension' is {}", sizes->size(), *dimension));
  }
  for (std::size_t a = 0; a < sizes->size(); ++a) {
    const std::int64_t s = (*sizes)[a];
    if (s <= 0 || s > std::numeric_limits<int>::max()) {
      fail(path, fmt::format("'sizes' entry {} is {}; sizes must be positive and fit in an int", a + 1, s));
    }
  }

  // kinds: a leading vector axis would be colour or vector voxels, which a
  // scalar volume cannot hold.
  if (const std::string* kinds = find_field(header, {"kinds"})) {
    const auto words = split_words(*kinds);
    if (!words.empty()) {
      const std::string first = to_lower(words.front());
      static const std::array<std::string_view, 7> kScalarAxisKinds = {"domain", "space", "time", "???",
                                                                        "none",   "list",  "scalar"};
      bool scalar_axis = false;
      for (std::string_view k : kScalarAxisKinds) scalar_axis = scalar_axis || first == k;
      if (!scalar_axis) {
        fail(path, fmt::format("the first axis has kind '{}'; penumbra reads scalar voxels only", words.front()));
      }
    }
  }

  // type and byte order
  VolumeLayout layout;
  const std::string* type_text = find_field(header, {"type"});
  if (!type_text) fail(path, "the required field 'type' is missing");
  const auto type = nrrd_type(*type_text);
  if (!type) {
    fail(path, fmt::format("type '{}' is not supported (8-, 16- and 32-bit integers, float and double are)",
                           *type_text));
  }
  layout.type = *type;
  if (const std::string* endian = find_field(header, {"endian"})) {
    if (equals_ignore_case(*endian, "little")) {
      layout.byte_order = std::endian::little;
    } else if (equals_ignore_case(*endian, "big")) {
      layout.byte_order = std::endian::big;
    } else {
      fail(path, fmt::format("'endian' should be 'little' or 'big', got '{}'", *endian));
    }
  }

  layout.dims = ivec3(int((*sizes)[0]), int((*sizes)[1]), int((*sizes)[2]));
  layout.frame_count = *dimension == 4 ? int((*sizes)[3]) : 1;

  // spacing: "spacings" or the lengths of the "space directions"
  const std::string* spacings_text = find_field(header, {"spacings"});
  const std::string* directions_text = find_field(header, {"space directions"});
  std::array<double, 3> spacing = {1.0, 1.0, 1.0};
  if (spacings_text) {
    const auto values = parse_doubles(*spacings_text);
    if (!values) fail(path, fmt::format("'spacings' should be numbers, got '{}'", *spacings_text));
    if (static_cast<std::int64_t>(values->size()) != *dimension) {
      fail(path, fmt::format("'spacings' has {} entries but 'dimension' is {}", values->size(), *dimension));
    }
    for (int a = 0; a < 3; ++a) spacing[a] = (*values)[a];
  } else if (directions_text) {
    const auto vectors = parse_vectors(path, "space directions", *directions_text);
    if (static_cast<std::int64_t>(vectors.size()) != *dimension) {
      fail(path, fmt::format("'space directions' has {} entries but 'dimension' is {}", vectors.size(), *dimension));
    }
    for (int a = 0; a < 3; ++a) {
      if (!vectors[a]) {
        spacing[a] = std::nan("");
        continue;
      }
      double length_squared = 0.0;
      for (double c : *vectors[a]) length_squared += c * c;
      spacing[a] = std::sqrt(length_squared);
    }
  }
  for (int a = 0; a < 3; ++a) {
    // NaN is NRRD's "unknown"; use unit spacing as the README asks for such data.
    if (std::isnan(spacing[a])) spacing[a] = 1.0;
    // A negative spacing (a flipped axis) keeps its magnitude: penumbra's
    // index-to-world map has no flips.
    const std::optional<float> magnitude = to_float(std::fabs(spacing[a]));
    if (!std::isfinite(spacing[a]) || !magnitude || !(*magnitude > 0.0f)) {
      fail(path, fmt::format("axis {} has spacing {}; spacings must be finite, non-zero and within the float range",
                             a + 1, spacing[a]));
    }
    layout.spacing[a] = *magnitude;
  }
  if (const std::string* origin_text = find_field(header, {"space origin"})) {
    const auto vectors = parse_vectors(path, "space origin", *origin_text);
    if (vectors.size() != 1 || !vectors[0] || vectors[0]->size() < 2 || vectors[0]->size() > 4) {
      fail(path, fmt::format("'space origin' should be one vector like (0,0,0), got '{}'", *origin_text));
    }
    const std::vector<double>& o = *vectors[0];
    layout.origin = vec3(float(o[0]), float(o[1]), o.size() > 2 ? float(o[2]) : 0.0f);
  }

  // encoding and data files
  const std::string* encoding_text = find_field(header, {"encoding"});
  if (!encoding_text) fail(path, "the required field 'encoding' is missing");
  const std::string encoding = to_lower(*encoding_text);
  PayloadSource prototype;
  if (encoding == "raw") {
    prototype.encoding = PayloadEncoding::Raw;
  } else if (encoding == "gzip" || encoding == "gz") {
    prototype.encoding = PayloadEncoding::Compressed;
  } else {
    fail(path, fmt::format("encoding '{}' is not supported (raw and gzip are)", *encoding_text));
  }
  const std::int64_t line_skip = int_field(path, header, "line skip", 0);
  const std::int64_t byte_skip = int_field(path, header, "byte skip", 0);
  if (line_skip < 0) fail(path, fmt::format("'line skip' must not be negative, got {}", line_skip));
  if (byte_skip < -1) fail(path, fmt::format("'byte skip' must be -1 or more, got {}", byte_skip));
  if (byte_skip == -1 && prototype.encoding != PayloadEncoding::Raw) {
    fail(path, "'byte skip: -1' (data at the end of the file) needs 'encoding: raw'");
  }

  std::vector<std::filesystem::path> files;
  std::uint64_t start = 0;  // where line skip counts from
  const std::string* data_file = find_field(header, {"data file", "datafile"});
  if (!data_file) {
    files.push_back(path);
    start = header.data_offset;
  } else {
    const auto words = split_words(*data_file);
    if (words.empty()) fail(path, "'data file' is empty");
    // With several files, each holds a slab of `subdim` axes; the default is
    // one slice along the slowest axis per file.
    const auto subdim_of = [&](std::size_t index) -> std::int64_t {
      if (words.size() <= index) return *dimension - 1;
      const auto v = parse_int(words[index]);
      if (!v || *v < 1 || *v > *dimension) {
        fail(path, fmt::format("'data file' subdimension should be 1 to {}, got '{}'", *dimension, words[index]));
      }
      return *v;
    };
    const auto files_needed = [&](std::int64_t subdim) {
      std::uint64_t count = 1;
      for (std::int64_t a = subdim; a < *dimension; ++a) {
        count = checked_product({count, std::uint64_t((*sizes)[static_cast<std::size_t>(a)])});
      }
      return count;
    };
    if (words.front() == "LIST") {
      if (words.size() > 2) fail(path, "'data file: LIST' takes at most one subdimension");
      const std::uint64_t needed = files_needed(subdim_of(1));
      if (header.listed_files.size() != needed) {
        fail(path, fmt::format("'data file: LIST' names {} files, but 'sizes' needs {}", header.listed_files.size(),
                               needed));
      }
      for (const std::string& name : header.listed_files) files.push_back(resolve_data_file(path, name));
    } else if (words.size() >= 4 && words.front().find('%') != std::string_view::npos) {
      if (words.size() > 5) fail(path, "'data file' pattern takes: format min max step [subdim]");
      const auto first = parse_int(words[1]);
      const auto last = parse_int(words[2]);
      const auto step = parse_int(words[3]);
      if (!first || !last || !step) fail(path, fmt::format("'data file' pattern needs integer min max step: '{}'",
                                                           *data_file));
      const std::uint64_t needed = files_needed(subdim_of(4));
      std::string error;
      const auto names = expand_file_pattern(words.front(), *first, *last, *step, needed, error);
      if (!names) fail(path, "'data file' " + error);
      if (names->size() != needed) {
        fail(path, fmt::format("'data file' pattern gives {} files, but 'sizes' needs {}", names->size(), needed));
      }
      for (const std::string& name : *names) files.push_back(resolve_data_file(path, name));
    } else {
      // One file; its name may contain spaces.
      files.push_back(resolve_data_file(path, *data_file));
    }
  }

  std::vector<PayloadSource> payloads;
  for (const std::filesystem::path& file : files) {
    PayloadSource source = prototype;
    source.file = file;
    source.offset = offset_after_lines(file, start, static_cast<std::uint64_t>(line_skip));
    if (byte_skip == -1) {
      source.at_end = true;
    } else if (source.encoding == PayloadEncoding::Raw) {
      source.offset += static_cast<std::uint64_t>(byte_skip);
    } else {
      source.skip_after_decoding = static_cast<std::uint64_t>(byte_skip);
    }
    payloads.push_back(std::move(source));
  }
  return load_volume(path, layout, payloads);
}

}  // namespace penumbra

#include "penumbra/io/dat_reader.h"

#include "penumbra/base/error.h"
#include "penumbra/io/binary_file.h"
#include "penumbra/io/text_header.h"
#include "penumbra/io/text_parsing.h"
#include "penumbra/io/volume_layout.h"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <map>

namespace penumbra {
namespace {

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& what) {
  throw IoError(display_path(path), ".dat header: " + what);
}

std::optional<VoxelType> dat_type(std::string_view name) {
  static const std::map<std::string, VoxelType, std::less<>> kTypes = {
      {"uchar", VoxelType::UInt8},    {"uint8", VoxelType::UInt8},     {"char", VoxelType::Int8},
      {"int8", VoxelType::Int8},      {"ushort", VoxelType::UInt16},   {"ushort_12", VoxelType::UInt16},
      {"uint16", VoxelType::UInt16},  {"uint12", VoxelType::UInt16},   {"short", VoxelType::Int16},
      {"int16", VoxelType::Int16},    {"uint", VoxelType::UInt32},     {"uint32", VoxelType::UInt32},
      {"int", VoxelType::Int32},      {"int32", VoxelType::Int32},     {"float", VoxelType::Float32},
      {"float32", VoxelType::Float32}, {"double", VoxelType::Float64}, {"float64", VoxelType::Float64},
  };
  const auto it = kTypes.find(to_lower(trim(name)));
  if (it == kTypes.end()) return std::nullopt;
  return it->second;
}

}  // namespace

std::shared_ptr<Volume> read_dat(const std::filesystem::path& path) {
  const TextHeader text = read_text_header(path, [](std::string_view) { return false; }, 1u << 20);
  std::map<std::string, std::string, std::less<>> fields;
  for (std::size_t n = 0; n < text.lines.size(); ++n) {
    const std::string_view line = trim(text.lines[n]);
    if (line.empty() || line.front() == '#') continue;
    const std::size_t colon = line.find(':');
    if (colon == std::string_view::npos) {
      fail(path, fmt::format("line {} is not 'Key: value': '{}'", n + 1, line));
    }
    fields[to_lower(trim(line.substr(0, colon)))] = std::string(trim(line.substr(colon + 1)));
  }
  const auto field = [&](std::initializer_list<std::string_view> names) -> const std::string* {
    for (std::string_view name : names) {
      const auto it = fields.find(name);
      if (it != fields.end()) return &it->second;
    }
    return nullptr;
  };

  const std::string* file_name = field({"objectfilename", "rawfile"});
  if (!file_name || file_name->empty()) fail(path, "'ObjectFileName' is missing");
  const std::string* resolution = field({"resolution", "dimension", "dimensions"});
  if (!resolution) fail(path, "'Resolution' is missing");
  const std::string* format = field({"format"});
  if (!format) fail(path, "'Format' is missing");

  VolumeLayout layout;
  const auto dims = parse_ints(*resolution);
  if (!dims || (dims->size() != 3 && dims->size() != 4)) {
    fail(path, fmt::format("'Resolution' should be three integers, got '{}'", *resolution));
  }
  for (std::size_t a = 0; a < dims->size(); ++a) {
    if ((*dims)[a] <= 0 || (*dims)[a] > std::numeric_limits<int>::max()) {
      fail(path, fmt::format("'Resolution' entry {} is {}; it must be positive", a + 1, (*dims)[a]));
    }
  }
  layout.dims = ivec3(int((*dims)[0]), int((*dims)[1]), int((*dims)[2]));
  if (dims->size() == 4) layout.frame_count = int((*dims)[3]);

  const auto type = dat_type(*format);
  if (!type) {
    fail(path, fmt::format("Format '{}' is not supported (UCHAR, CHAR, USHORT, SHORT, UINT, INT, FLOAT, DOUBLE are)",
                           *format));
  }
  layout.type = *type;

  if (const std::string* model = field({"objectmodel"})) {
    if (!equals_ignore_case(*model, "I") && !equals_ignore_case(*model, "L")) {
      fail(path, fmt::format("ObjectModel '{}' has several channels; penumbra reads scalar volumes ('I')", *model));
    }
  }
  if (const std::string* order = field({"byteorder", "endianness"})) {
    if (equals_ignore_case(*order, "LittleEndian") || equals_ignore_case(*order, "little")) {
      layout.byte_order = std::endian::little;
    } else if (equals_ignore_case(*order, "BigEndian") || equals_ignore_case(*order, "big")) {
      layout.byte_order = std::endian::big;
    } else {
      fail(path, fmt::format("ByteOrder should be LittleEndian or BigEndian, got '{}'", *order));
    }
  }
  if (const std::string* thickness = field({"slicethickness", "spacing"})) {
    const auto values = parse_doubles(*thickness);
    if (!values || values->size() < 3) {
      fail(path, fmt::format("'SliceThickness' should be three numbers, got '{}'", *thickness));
    }
    for (int a = 0; a < 3; ++a) {
      const double s = (*values)[static_cast<std::size_t>(a)];
      if (!(s > 0.0) || !std::isfinite(s)) {
        fail(path, fmt::format("'SliceThickness' entry {} is {}; it must be positive", a + 1, s));
      }
      layout.spacing[a] = static_cast<float>(s);
    }
  }

  PayloadSource source;
  const std::filesystem::path raw(*file_name);
  source.file = raw.is_absolute() ? raw : path.parent_path() / raw;
  if (const std::string* offset = field({"byteoffset", "headerskip"})) {
    const auto value = parse_int(*offset);
    if (!value || *value < 0) fail(path, fmt::format("'ByteOffset' should be a non-negative integer, got '{}'", *offset));
    source.offset = static_cast<std::uint64_t>(*value);
  }
  return load_volume(path, layout, {source});
}

}  // namespace penumbra

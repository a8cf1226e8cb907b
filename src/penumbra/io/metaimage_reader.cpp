#include "penumbra/io/metaimage_reader.h"

#include "penumbra/base/error.h"
#include "penumbra/base/memory_budget.h"
#include "penumbra/io/binary_file.h"
#include "penumbra/io/file_pattern.h"
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
  throw IoError(display_path(path), "MetaImage header: " + what);
}

std::optional<VoxelType> met_type(std::string_view name) {
  static const std::map<std::string, VoxelType, std::less<>> kTypes = {
      {"met_uchar", VoxelType::UInt8},  {"met_char", VoxelType::Int8},     {"met_ushort", VoxelType::UInt16},
      {"met_short", VoxelType::Int16},  {"met_uint", VoxelType::UInt32},   {"met_int", VoxelType::Int32},
      {"met_float", VoxelType::Float32}, {"met_double", VoxelType::Float64},
  };
  const auto it = kTypes.find(to_lower(trim(name)));
  if (it == kTypes.end()) return std::nullopt;
  return it->second;
}

// The header ends with ElementDataFile, except that "LIST" is followed by
// the file names (up to the end of the file).
bool ends_header(std::string_view line) {
  const std::size_t equals = line.find('=');
  if (equals == std::string_view::npos || !equals_ignore_case(trim(line.substr(0, equals)), "ElementDataFile")) {
    return false;
  }
  const auto words = split_words(line.substr(equals + 1));
  return words.empty() || !equals_ignore_case(words.front(), "LIST");
}

std::optional<bool> parse_bool(std::string_view text) {
  if (equals_ignore_case(text, "true") || text == "1") return true;
  if (equals_ignore_case(text, "false") || text == "0") return false;
  return std::nullopt;
}

}  // namespace

std::shared_ptr<Volume> read_metaimage(const std::filesystem::path& path) {
  const TextHeader text = read_text_header(path, ends_header);
  std::map<std::string, std::string, std::less<>> fields;
  std::vector<std::string> listed_files;
  bool data_file_seen = false;
  for (std::size_t n = 0; n < text.lines.size(); ++n) {
    const std::string_view line = trim(text.lines[n]);
    if (data_file_seen) {
      if (!line.empty()) listed_files.emplace_back(line);
      continue;
    }
    if (line.empty() || line.front() == '#') continue;
    const std::size_t equals = line.find('=');
    if (equals == std::string_view::npos) fail(path, fmt::format("line {} is not 'Key = Value': '{}'", n + 1, line));
    const std::string key = to_lower(trim(line.substr(0, equals)));
    fields[key] = std::string(trim(line.substr(equals + 1)));
    if (key == "elementdatafile") data_file_seen = true;
  }
  const auto field = [&](std::initializer_list<std::string_view> names) -> const std::string* {
    for (std::string_view name : names) {
      const auto it = fields.find(name);
      if (it != fields.end()) return &it->second;
    }
    return nullptr;
  };
  const auto required = [&](std::string_view name) -> const std::string& {
    const std::string* value = field({name});
    if (!value) fail(path, fmt::format("the required key '{}' is missing", name));
    return *value;
  };

  const std::string& ndims_text = required("ndims");
  const auto ndims = parse_int(ndims_text);
  if (!ndims || (*ndims != 3 && *ndims != 4)) {
    fail(path, fmt::format("NDims is '{}'; penumbra reads 3D volumes and 4D time series", ndims_text));
  }
  const std::string& dims_text = required("dimsize");
  const auto dims = parse_ints(dims_text);
  if (!dims) fail(path, fmt::format("DimSize should be integers, got '{}'", dims_text));
  if (static_cast<std::int64_t>(dims->size()) != *ndims) {
    fail(path, fmt::format("DimSize has {} entries but NDims is {}", dims->size(), *ndims));
  }
  for (std::size_t a = 0; a < dims->size(); ++a) {
    if ((*dims)[a] <= 0 || (*dims)[a] > std::numeric_limits<int>::max()) {
      fail(path, fmt::format("DimSize entry {} is {}; sizes must be positive", a + 1, (*dims)[a]));
    }
  }
  VolumeLayout layout;
  layout.dims = ivec3(int((*dims)[0]), int((*dims)[1]), int((*dims)[2]));
  layout.frame_count = *ndims == 4 ? int((*dims)[3]) : 1;

  const std::string& type_text = required("elementtype");
  const auto type = met_type(type_text);
  if (!type) {
    fail(path, fmt::format("ElementType '{}' is not supported (MET_CHAR, MET_UCHAR, MET_SHORT, MET_USHORT, "
                           "MET_INT, MET_UINT, MET_FLOAT, MET_DOUBLE are)",
                           type_text));
  }
  layout.type = *type;
  if (const std::string* channels = field({"elementnumberofchannels"}); channels && trim(*channels) != "1") {
    fail(path, fmt::format("ElementNumberOfChannels is {}; penumbra reads scalar volumes", *channels));
  }
  if (const std::string* msb = field({"binarydatabyteordermsb", "elementbyteordermsb"})) {
    const auto big = parse_bool(*msb);
    if (!big) fail(path, fmt::format("BinaryDataByteOrderMSB should be True or False, got '{}'", *msb));
    layout.byte_order = *big ? std::endian::big : std::endian::little;
  }
  if (const std::string* spacing = field({"elementspacing", "elementsize"})) {
    const auto values = parse_doubles(*spacing);
    if (!values || static_cast<std::int64_t>(values->size()) != *ndims) {
      fail(path, fmt::format("ElementSpacing should be {} numbers, got '{}'", *ndims, *spacing));
    }
    for (int a = 0; a < 3; ++a) {
      const double s = std::fabs((*values)[static_cast<std::size_t>(a)]);
      if (!(s > 0.0) || !std::isfinite(s)) {
        fail(path, fmt::format("ElementSpacing entry {} is {}; spacing must be non-zero", a + 1, s));
      }
      layout.spacing[a] = static_cast<float>(s);
    }
  }
  if (const std::string* offset = field({"offset", "origin", "position"})) {
    const auto values = parse_doubles(*offset);
    if (!values || values->size() < 3) fail(path, fmt::format("Offset should be {} numbers, got '{}'", *ndims, *offset));
    layout.origin = vec3(float((*values)[0]), float((*values)[1]), float((*values)[2]));
  }

  PayloadSource prototype;
  if (const std::string* compressed = field({"compresseddata"})) {
    const auto value = parse_bool(*compressed);
    if (!value) fail(path, fmt::format("CompressedData should be True or False, got '{}'", *compressed));
    prototype.encoding = *value ? PayloadEncoding::Compressed : PayloadEncoding::Raw;
  }
  if (const std::string* size = field({"compresseddatasize"}); size && prototype.encoding == PayloadEncoding::Compressed) {
    const auto value = parse_int(*size);
    if (!value || *value <= 0) fail(path, fmt::format("CompressedDataSize should be a positive integer, got '{}'", *size));
    prototype.compressed_size = static_cast<std::uint64_t>(*value);
  }
  std::int64_t header_size = 0;
  if (const std::string* skip = field({"headersize"})) {
    const auto value = parse_int(*skip);
    if (!value || *value < -1) fail(path, fmt::format("HeaderSize should be -1 or more, got '{}'", *skip));
    header_size = *value;
    if (header_size == -1 && prototype.encoding != PayloadEncoding::Raw) {
      fail(path, "HeaderSize = -1 (data at the end of the file) needs uncompressed data");
    }
  }

  const std::string& data_file = required("elementdatafile");
  const auto words = split_words(data_file);
  if (words.empty()) fail(path, "ElementDataFile is empty");
  const auto resolve = [&](std::string_view name) {
    const std::filesystem::path file{std::string(trim(name))};
    return file.is_absolute() ? file : path.parent_path() / file;
  };
  const auto files_needed = [&](std::size_t subdim_word) {
    std::int64_t subdim = *ndims - 1;
    if (words.size() > subdim_word) {
      const auto value = parse_int(words[subdim_word]);
      if (!value || *value < 1 || *value > *ndims) {
        fail(path, fmt::format("ElementDataFile subdimension should be 1 to {}, got '{}'", *ndims, words[subdim_word]));
      }
      subdim = *value;
    }
    std::uint64_t count = 1;
    for (std::int64_t a = subdim; a < *ndims; ++a) {
      count = checked_product({count, std::uint64_t((*dims)[static_cast<std::size_t>(a)])});
    }
    return count;
  };

  std::vector<std::filesystem::path> files;
  std::uint64_t start = 0;
  if (equals_ignore_case(words.front(), "LOCAL")) {
    files.push_back(path);
    start = text.data_offset;
  } else if (equals_ignore_case(words.front(), "LIST")) {
    const std::uint64_t needed = files_needed(1);
    if (listed_files.size() != needed) {
      fail(path, fmt::format("ElementDataFile LIST names {} files, but DimSize needs {}", listed_files.size(), needed));
    }
    for (const std::string& name : listed_files) files.push_back(resolve(name));
  } else if (words.size() >= 4 && words.front().find('%') != std::string_view::npos) {
    const auto first = parse_int(words[1]);
    const auto last = parse_int(words[2]);
    const auto step = parse_int(words[3]);
    if (!first || !last || !step) fail(path, fmt::format("ElementDataFile pattern needs integers: '{}'", data_file));
    const std::uint64_t needed = files_needed(4);
    std::string error;
    const auto names = expand_file_pattern(words.front(), *first, *last, *step, needed, error);
    if (!names) fail(path, "ElementDataFile " + error);
    if (names->size() != needed) {
      fail(path, fmt::format("ElementDataFile pattern gives {} files, but DimSize needs {}", names->size(), needed));
    }
    for (const std::string& name : *names) files.push_back(resolve(name));
  } else {
    files.push_back(resolve(data_file));
  }

  std::vector<PayloadSource> payloads;
  for (const std::filesystem::path& file : files) {
    PayloadSource source = prototype;
    source.file = file;
    source.offset = start;
    if (header_size == -1) {
      source.at_end = true;
    } else {
      source.offset += static_cast<std::uint64_t>(header_size);
    }
    payloads.push_back(std::move(source));
  }
  return load_volume(path, layout, payloads);
}

}  // namespace penumbra

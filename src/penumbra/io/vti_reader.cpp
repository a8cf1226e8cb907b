#include "penumbra/io/vti_reader.h"

#include "penumbra/base/error.h"
#include "penumbra/base/memory_budget.h"
#include "penumbra/base/numeric_cast.h"
#include "penumbra/io/base64.h"
#include "penumbra/io/binary_file.h"
#include "penumbra/io/byte_order.h"
#include "penumbra/io/compression.h"
#include "penumbra/io/text_parsing.h"
#include "penumbra/io/volume_bytes.h"
#include "penumbra/io/xml_scanner.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>

namespace penumbra {
namespace {

struct VtiContext {
  std::string path;
  std::endian byte_order = std::endian::little;
  int header_word = 4;  // UInt32 or UInt64 header_type
  bool compressed = false;

  [[noreturn]] void fail(const std::string& what) const { throw IoError(path, "VTI: " + what); }
};

std::optional<VoxelType> vtk_type(std::string_view name) {
  static const std::map<std::string, VoxelType, std::less<>> kTypes = {
      {"Int8", VoxelType::Int8},     {"UInt8", VoxelType::UInt8},     {"Int16", VoxelType::Int16},
      {"UInt16", VoxelType::UInt16}, {"Int32", VoxelType::Int32},     {"UInt32", VoxelType::UInt32},
      {"Float32", VoxelType::Float32}, {"Float64", VoxelType::Float64},
      // Names that old VTK writers used.
      {"Char", VoxelType::Int8},     {"UnsignedChar", VoxelType::UInt8}, {"Short", VoxelType::Int16},
      {"UnsignedShort", VoxelType::UInt16}, {"Int", VoxelType::Int32}, {"UnsignedInt", VoxelType::UInt32},
      {"Float", VoxelType::Float32}, {"Double", VoxelType::Float64},
  };
  const auto it = kTypes.find(name);
  if (it == kTypes.end()) return std::nullopt;
  return it->second;
}

// Where the bytes of a binary DataArray come from: raw bytes in the file, or
// base64 text (inline, or appended with encoding="base64").
class ByteSource {
 public:
  ByteSource(const VtiContext& context, std::span<const std::byte> raw) : context_(context), raw_(raw) {}
  ByteSource(const VtiContext& context, std::string_view base64) : context_(context), decoder_(Base64Decoder(base64)) {
    base64_ = true;
  }

  void read(std::span<std::byte> out, const char* what) {
    if (base64_) {
      if (!decoder_->read_exact(out)) context_.fail(fmt::format("bad base64 in {}: {}", what, decoder_->error()));
      return;
    }
    if (out.size() > raw_.size()) {
      context_.fail(fmt::format("{} is truncated: needs {} bytes, {} are left in the file", what, out.size(),
                                raw_.size()));
    }
    std::memcpy(out.data(), raw_.data(), out.size());
    raw_ = raw_.subspan(out.size());
  }

  std::uint64_t read_word(const char* what) {
    std::byte bytes[8];
    const std::span<std::byte> word(bytes, static_cast<std::size_t>(context_.header_word));
    read(word, what);
    convert_byte_order(word, word.size(), context_.byte_order);
    if (context_.header_word == 4) {
      std::uint32_t v;
      std::memcpy(&v, bytes, 4);
      return v;
    }
    std::uint64_t v;
    std::memcpy(&v, bytes, 8);
    return v;
  }

  // Upper bound of the bytes left, to reject impossible sizes before
  // allocating.
  std::uint64_t available() const { return base64_ ? decoder_->remaining_bound() : raw_.size(); }

 private:
  const VtiContext& context_;
  std::span<const std::byte> raw_;
  std::optional<Base64Decoder> decoder_;
  bool base64_ = false;
};

void read_binary_array(const VtiContext& context, ByteSource& source, Volume& volume) {
  const std::uint64_t expected = volume.frame_bytes();
  std::byte* out = volume.frame_data(0);
  if (!context.compressed) {
    const std::uint64_t size = source.read_word("the DataArray header");
    if (size != expected) {
      context.fail(fmt::format("the DataArray holds {} bytes, but WholeExtent and type need {}", size, expected));
    }
    source.read(std::span(out, static_cast<std::size_t>(expected)), "the DataArray data");
    return;
  }
  // vtkZLibDataCompressor: [block count, block size, last block size (0 =
  // full), compressed size of each block], then the zlib blocks.
  const std::uint64_t blocks = source.read_word("the compression header");
  const std::uint64_t block_size = source.read_word("the compression header");
  const std::uint64_t last_size = source.read_word("the compression header");
  if (blocks > source.available() / std::uint64_t(context.header_word) + 1) {
    context.fail(fmt::format("the compression header claims {} blocks, more than the file holds", blocks));
  }
  const std::uint64_t last = blocks == 0 ? 0 : (last_size == 0 ? block_size : last_size);
  const std::uint64_t total = blocks == 0 ? 0 : checked_product({blocks - 1, block_size}) + last;
  if (total != expected || (blocks > 0 && last > block_size)) {
    context.fail(fmt::format("the compressed DataArray holds {} bytes ({} blocks of {}), but WholeExtent and type "
                             "need {}",
                             total, blocks, block_size, expected));
  }
  std::vector<std::uint64_t> compressed_sizes(static_cast<std::size_t>(blocks));
  std::uint64_t compressed_total = 0;
  for (std::uint64_t& size : compressed_sizes) {
    size = source.read_word("the compression header");
    compressed_total += size;
    if (compressed_total > source.available()) {
      context.fail(fmt::format("the compressed blocks need {} bytes, more than the file holds", compressed_total));
    }
  }
  std::vector<std::byte> compressed;
  for (std::uint64_t b = 0; b < blocks; ++b) {
    compressed.resize(static_cast<std::size_t>(compressed_sizes[b]));
    source.read(compressed, "a compressed block");
    const std::uint64_t size = b + 1 == blocks ? last : block_size;
    InflateStream(compressed, context.path).read_exact(std::span(out + b * block_size, static_cast<std::size_t>(size)),
                                                       fmt::format("compressed block {}", b));
  }
}

template <class T> bool parse_ascii_value(std::string_view token, T& out) {
  if constexpr (std::is_floating_point_v<T>) {
    const auto d = parse_double(token);
    if (!d) return false;
    if constexpr (std::is_same_v<T, float>) {
      // A Float32 array may hold NaN and infinities, but not 1e300.
      const auto f = to_float(*d);
      if (!f) return false;
      out = *f;
    } else {
      out = static_cast<T>(*d);
    }
    return true;
  } else {
    T v = 0;
    const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
    if (ec == std::errc() && end == token.data() + token.size()) {
      out = v;
      return true;
    }
    // Some writers print integers as "12.0"; 1e30, inf and NaN are no Int16.
    const auto d = parse_double(token);
    const std::optional<T> whole = d ? to_exact_integer<T>(*d) : std::nullopt;
    if (!whole) return false;
    out = *whole;
    return true;
  }
}

void read_ascii_array(const VtiContext& context, std::string_view text, Volume& volume) {
  visit_voxel_type(volume.type(), [&](auto tag) {
    using T = decltype(tag);
    T* out = volume.frame_as<T>(0);
    const std::uint64_t count = volume.voxel_count();
    std::uint64_t n = 0;
    std::size_t i = 0;
    while (i < text.size()) {
      while (i < text.size() && (text[i] == ' ' || text[i] == '\n' || text[i] == '\r' || text[i] == '\t')) ++i;
      const std::size_t start = i;
      while (i < text.size() && !(text[i] == ' ' || text[i] == '\n' || text[i] == '\r' || text[i] == '\t')) ++i;
      if (i == start) break;
      if (n == count) context.fail(fmt::format("the ascii DataArray has more than the {} values WholeExtent needs", count));
      if (!parse_ascii_value(text.substr(start, i - start), out[n])) {
        context.fail(fmt::format("ascii value {} '{}' is not a valid {}", n, text.substr(start, i - start),
                                 to_string(volume.type())));
      }
      ++n;
    }
    if (n != count) context.fail(fmt::format("the ascii DataArray has {} values, but WholeExtent needs {}", n, count));
  });
}

std::optional<std::vector<double>> numbers(const XmlTag& tag, std::string_view name) {
  const std::string* value = tag.attribute(name);
  if (!value) return std::nullopt;
  return parse_doubles(*value);
}

struct ArrayInfo {
  XmlTag tag;
  std::size_t content_begin = 0;  // inline text between <DataArray> and </DataArray>
  std::size_t content_end = 0;
};

}  // namespace

std::shared_ptr<Volume> read_vti(const std::filesystem::path& path) {
  const std::vector<std::byte> file = read_whole_file(path);
  const std::string_view text(reinterpret_cast<const char*>(file.data()), file.size());
  VtiContext context;
  context.path = display_path(path);
  XmlScanner scanner(text, context.path);

  std::optional<XmlTag> image_data;
  std::optional<XmlTag> piece;
  std::string scalars_name;
  std::vector<ArrayInfo> arrays;
  std::optional<XmlTag> appended;
  bool root_seen = false;
  bool in_point_data = false;
  std::optional<ArrayInfo> open_array;
  while (auto tag = scanner.next()) {
    const bool start = tag->kind != XmlTag::Kind::End;
    if (!root_seen) {
      if (tag->name != "VTKFile") context.fail(fmt::format("the root element is <{}>, not <VTKFile>", tag->name));
      root_seen = true;
      const std::string* type = tag->attribute("type");
      if (!type || *type != "ImageData") {
        context.fail(fmt::format("VTKFile type is '{}'; penumbra reads ImageData", type ? *type : ""));
      }
      if (const std::string* order = tag->attribute("byte_order")) {
        if (*order == "BigEndian") {
          context.byte_order = std::endian::big;
        } else if (*order != "LittleEndian") {
          context.fail(fmt::format("byte_order '{}' is neither LittleEndian nor BigEndian", *order));
        }
      }
      if (const std::string* header = tag->attribute("header_type")) {
        if (*header == "UInt64") {
          context.header_word = 8;
        } else if (*header != "UInt32") {
          context.fail(fmt::format("header_type '{}' is neither UInt32 nor UInt64", *header));
        }
      }
      if (const std::string* compressor = tag->attribute("compressor"); compressor && !compressor->empty()) {
        if (*compressor != "vtkZLibDataCompressor") {
          context.fail(fmt::format("compressor '{}' is not supported (vtkZLibDataCompressor is)", *compressor));
        }
        context.compressed = true;
      }
      continue;
    }
    if (tag->name == "ImageData" && start) {
      image_data = *tag;
    } else if (tag->name == "Piece" && start) {
      if (piece) context.fail("the file has several pieces; penumbra reads single-piece ImageData");
      piece = *tag;
    } else if (tag->name == "PointData") {
      in_point_data = tag->kind == XmlTag::Kind::Start;
      if (start) {
        if (const std::string* scalars = tag->attribute("Scalars")) scalars_name = *scalars;
      }
    } else if (tag->name == "DataArray" && in_point_data) {
      if (tag->kind == XmlTag::Kind::Start) {
        open_array = ArrayInfo{*tag, tag->end, tag->end};
      } else if (tag->kind == XmlTag::Kind::SelfClosing) {
        arrays.push_back(ArrayInfo{*tag, tag->end, tag->end});
      } else if (open_array) {
        open_array->content_end = tag->begin;
        arrays.push_back(std::move(*open_array));
        open_array.reset();
      }
    } else if (tag->name == "AppendedData" && start) {
      appended = *tag;
      break;  // binary follows; nothing after it is XML we need
    }
  }
  if (!root_seen) context.fail("no <VTKFile> element; not a VTK XML file");
  if (!image_data) context.fail("no <ImageData> element");
  if (arrays.empty()) context.fail("no PointData DataArray (penumbra reads point data)");

  const ArrayInfo* chosen = &arrays.front();
  if (!scalars_name.empty()) {
    chosen = nullptr;
    for (const ArrayInfo& a : arrays) {
      const std::string* name = a.tag.attribute("Name");
      if (name && *name == scalars_name) chosen = &a;
    }
    if (!chosen) context.fail(fmt::format("PointData names Scalars=\"{}\" but has no such DataArray", scalars_name));
  }
  const XmlTag& array = chosen->tag;

  // Geometry.
  const auto extent = numbers(*image_data, "WholeExtent");
  if (!extent || extent->size() != 6) context.fail("ImageData needs WholeExtent with six integers");
  ivec3 dims;
  for (int a = 0; a < 3; ++a) {
    const double lo = (*extent)[static_cast<std::size_t>(2 * a)];
    const double hi = (*extent)[static_cast<std::size_t>(2 * a + 1)];
    const double size = hi - lo + 1.0;
    if (!(lo == std::floor(lo) && hi == std::floor(hi))) {
      context.fail(fmt::format("WholeExtent axis {} is {} to {}; extents are integers", a + 1, lo, hi));
    }
    if (!(size >= 1.0)) {
      context.fail(fmt::format("WholeExtent axis {} is {} to {}; it must hold at least one point", a + 1, lo, hi));
    }
    const auto points = to_integer<int>(size);
    if (!points) {
      context.fail(fmt::format("WholeExtent axis {} is {} to {}: {} points, more than the {} an axis can have", a + 1,
                               lo, hi, size, std::numeric_limits<int>::max()));
    }
    dims[a] = *points;
  }
  if (piece) {
    if (const auto piece_extent = numbers(*piece, "Extent"); piece_extent && *piece_extent != *extent) {
      context.fail("the piece's Extent differs from WholeExtent; penumbra reads complete single-piece files");
    }
  }
  vec3 spacing(1.0f);
  if (const auto s = numbers(*image_data, "Spacing")) {
    if (s->size() != 3) context.fail("Spacing should be three numbers");
    for (int a = 0; a < 3; ++a) {
      const double v = std::fabs((*s)[static_cast<std::size_t>(a)]);
      if (!(v > 0.0) || !std::isfinite(v)) context.fail(fmt::format("Spacing entry {} is {}; it must be non-zero", a + 1, v));
      spacing[a] = static_cast<float>(v);
    }
  }
  std::optional<vec3> origin;
  if (const auto o = numbers(*image_data, "Origin")) {
    if (o->size() != 3) context.fail("Origin should be three numbers");
    origin = vec3(float((*o)[0] + (*extent)[0] * spacing.x), float((*o)[1] + (*extent)[2] * spacing.y),
                  float((*o)[2] + (*extent)[4] * spacing.z));
    if (!is_finite(origin->x) || !is_finite(origin->y) || !is_finite(origin->z)) context.fail("Origin is not finite");
  }

  // The array.
  const std::string* type_name = array.attribute("type");
  if (!type_name) context.fail("the DataArray has no type");
  const auto type = vtk_type(*type_name);
  if (!type) context.fail(fmt::format("DataArray type '{}' is not supported (Int8 .. Float64 without 64-bit "
                                      "integers)",
                                      *type_name));
  if (const std::string* components = array.attribute("NumberOfComponents"); components && trim(*components) != "1") {
    context.fail(fmt::format("the DataArray has {} components; penumbra reads scalar volumes", *components));
  }
  const std::string* format_attribute = array.attribute("format");
  const std::string format = format_attribute ? *format_attribute : "ascii";
  const std::uint64_t expected =
      checked_product({std::uint64_t(dims.x), std::uint64_t(dims.y), std::uint64_t(dims.z), voxel_size(*type)});
  check_memory_budget(fmt::format("a {}x{}x{} {} volume from {}", dims.x, dims.y, dims.z, to_string(*type),
                                  context.path),
                      expected);

  // Reject sizes the file cannot hold before allocating.
  const std::string_view inline_text = text.substr(chosen->content_begin, chosen->content_end - chosen->content_begin);
  std::optional<ByteSource> source;
  if (format == "ascii") {
    if (expected / voxel_size(*type) > inline_text.size() / 2 + 1) {
      context.fail(fmt::format("the ascii DataArray has {} characters, too few for {} values", inline_text.size(),
                               expected / voxel_size(*type)));
    }
  } else if (format == "binary") {
    source.emplace(context, inline_text);
  } else if (format == "appended") {
    if (!appended) context.fail("the DataArray is appended but the file has no <AppendedData>");
    const std::string* offset_text = array.attribute("offset");
    const auto offset = offset_text ? parse_int(*offset_text) : std::nullopt;
    if (!offset || *offset < 0) context.fail("an appended DataArray needs a non-negative offset");
    const std::size_t underscore = text.find('_', appended->end);
    if (underscore == std::string_view::npos) context.fail("<AppendedData> has no '_' before its data");
    const std::size_t data_start = underscore + 1;
    if (static_cast<std::uint64_t>(*offset) > text.size() - data_start) {
      context.fail(fmt::format("the DataArray offset {} is past the end of the appended data", *offset));
    }
    const std::size_t begin = data_start + static_cast<std::size_t>(*offset);
    const std::string* encoding = appended->attribute("encoding");
    if (!encoding || *encoding == "raw") {
      source.emplace(context, std::span(file).subspan(begin));
    } else if (*encoding == "base64") {
      std::size_t end = text.find('<', begin);
      if (end == std::string_view::npos) end = text.size();
      source.emplace(context, text.substr(begin, end - begin));
    } else {
      context.fail(fmt::format("AppendedData encoding '{}' is neither raw nor base64", *encoding));
    }
  } else {
    context.fail(fmt::format("DataArray format '{}' is not ascii, binary or appended", format));
  }
  if (source) {
    const std::uint64_t available = source->available();
    const std::uint64_t limit = context.compressed ? max_inflated_size(available) : available;
    if (expected > limit) {
      context.fail(fmt::format("the DataArray needs {} bytes, more than the {} bytes of data in the file can hold",
                               expected, available));
    }
  }

  auto volume = std::make_shared<Volume>(dims, *type, 1);
  if (source) {
    read_binary_array(context, *source, *volume);
    convert_volume_byte_order(*volume, context.byte_order);
  } else {
    read_ascii_array(context, inline_text, *volume);
  }
  volume->set_spacing(spacing);
  if (origin) volume->set_origin(*origin);
  volume->set_source(context.path);
  return volume;
}

}  // namespace penumbra

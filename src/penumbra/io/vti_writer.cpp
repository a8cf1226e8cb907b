#include "penumbra/base/error.h"
#include "penumbra/base/memory_budget.h"
#include "penumbra/io/base64.h"
#include "penumbra/io/binary_file.h"
#include "penumbra/io/byte_order.h"
#include "penumbra/io/volume_writer.h"
#include "penumbra/io/voxel_output.h"

#include <fmt/format.h>
#include <zlib.h>

#include <cstring>

namespace penumbra {
namespace {

// VTK's default block size for vtkZLibDataCompressor.
constexpr std::size_t kBlockSize = 32768;

std::string_view vtk_type_name(VoxelType type) {
  switch (type) {
    case VoxelType::UInt8: return "UInt8";
    case VoxelType::Int8: return "Int8";
    case VoxelType::UInt16: return "UInt16";
    case VoxelType::Int16: return "Int16";
    case VoxelType::UInt32: return "UInt32";
    case VoxelType::Int32: return "Int32";
    case VoxelType::Float32: return "Float32";
    case VoxelType::Float64: return "Float64";
  }
  return "UInt8";
}

// Header words of the binary forms, in the file's byte order and width.
class HeaderWords {
 public:
  HeaderWords(const VtiWriteOptions& options) : options_(options) {}
  void add(std::uint64_t value) {
    std::byte word[8];
    const std::size_t size = options_.header_uint64 ? 8 : 4;
    if (size == 4) {
      const auto v = static_cast<std::uint32_t>(value);
      std::memcpy(word, &v, 4);
    } else {
      std::memcpy(word, &value, 8);
    }
    convert_byte_order(std::span(word, size), size, options_.byte_order);
    bytes_.insert(bytes_.end(), word, word + size);
  }
  const std::vector<std::byte>& bytes() const { return bytes_; }

 private:
  const VtiWriteOptions& options_;
  std::vector<std::byte> bytes_;
};

// The binary array as VTK lays it out: header words, then data (raw or as
// zlib blocks). Returned in two parts because VTK base64-encodes the
// compression header and the blocks as separate streams.
struct BinaryArray {
  std::vector<std::byte> header;
  std::vector<std::byte> data;
};

BinaryArray binary_array(const Volume& volume, const VtiWriteOptions& options) {
  std::vector<std::byte> raw = voxel_bytes(volume, options.frame, 1, options.byte_order, std::nullopt);
  HeaderWords header(options);
  if (!options.compress) {
    header.add(raw.size());
    return {header.bytes(), std::move(raw)};
  }
  const std::size_t blocks = (raw.size() + kBlockSize - 1) / kBlockSize;
  header.add(blocks);
  header.add(kBlockSize);
  header.add(raw.size() % kBlockSize);
  std::vector<std::byte> data;
  std::vector<std::byte> block(compressBound(kBlockSize));
  for (std::size_t b = 0; b < blocks; ++b) {
    const std::size_t size = std::min(kBlockSize, raw.size() - b * kBlockSize);
    uLongf compressed = static_cast<uLongf>(block.size());
    if (compress2(reinterpret_cast<Bytef*>(block.data()), &compressed,
                  reinterpret_cast<const Bytef*>(raw.data() + b * kBlockSize), static_cast<uLong>(size), 6) != Z_OK) {
      throw Error("zlib compression failed");
    }
    header.add(compressed);
    data.insert(data.end(), block.begin(), block.begin() + static_cast<std::ptrdiff_t>(compressed));
  }
  return {header.bytes(), std::move(data)};
}

std::string ascii_values(const Volume& volume, int frame) {
  std::string out;
  visit_voxel_type(volume.type(), [&](auto tag) {
    using T = decltype(tag);
    const T* values = volume.frame_as<T>(frame);
    for (std::uint64_t i = 0; i < volume.voxel_count(); ++i) {
      if constexpr (sizeof(T) == 1) {
        out += fmt::format("{}", int(values[i]));
      } else {
        out += fmt::format("{}", values[i]);
      }
      out += (i % 16 == 15) ? '\n' : ' ';
    }
  });
  return out;
}

}  // namespace

void write_vti(const std::filesystem::path& path, const Volume& volume, const VtiWriteOptions& options) {
  if (options.frame < 0 || options.frame >= volume.frame_count()) {
    throw InvalidArgument("frame", fmt::format("frame {} does not exist; the volume has {}", options.frame,
                                               volume.frame_count()));
  }
  // Every form but appended raw holds a copy of the voxels (and base64 4/3 of it).
  check_memory_budget(fmt::format("writing {}", display_path(path)), volume.frame_bytes() * 3);

  const ivec3 d = volume.dims();
  const vec3 s = volume.spacing();
  const vec3 o = volume.origin();
  const bool binary = options.format != VtiFormat::Ascii;
  const bool compressed = binary && options.compress;
  const std::string extent = fmt::format("0 {} 0 {} 0 {}", d.x - 1, d.y - 1, d.z - 1);

  std::string xml = "<?xml version=\"1.0\"?>\n";
  xml += fmt::format("<VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"{}\" header_type=\"{}\"{}>\n",
                     options.byte_order == std::endian::big ? "BigEndian" : "LittleEndian",
                     options.header_uint64 ? "UInt64" : "UInt32",
                     compressed ? " compressor=\"vtkZLibDataCompressor\"" : "");
  xml += fmt::format("  <ImageData WholeExtent=\"{}\" Origin=\"{} {} {}\" Spacing=\"{} {} {}\">\n", extent, o.x, o.y,
                     o.z, s.x, s.y, s.z);
  xml += fmt::format("    <Piece Extent=\"{}\">\n", extent);
  xml += "      <PointData Scalars=\"Scalars\">\n";
  const std::string array_start =
      fmt::format("        <DataArray type=\"{}\" Name=\"Scalars\" NumberOfComponents=\"1\" ", vtk_type_name(volume.type()));

  OutputFile out(path);
  const auto write_tail = [&](std::string_view appended_encoding) {
    xml += "      </PointData>\n      <CellData>\n      </CellData>\n    </Piece>\n  </ImageData>\n";
    if (!appended_encoding.empty()) xml += fmt::format("  <AppendedData encoding=\"{}\">\n   _", appended_encoding);
    out.write(xml);
    xml.clear();
  };

  switch (options.format) {
    case VtiFormat::Ascii:
      xml += array_start + "format=\"ascii\">\n" + ascii_values(volume, options.frame) + "\n        </DataArray>\n";
      write_tail({});
      break;
    case VtiFormat::Binary: {
      const BinaryArray array = binary_array(volume, options);
      const std::string encoded = compressed ? base64_encode(array.header) + base64_encode(array.data) : [&] {
        std::vector<std::byte> joined = array.header;
        joined.insert(joined.end(), array.data.begin(), array.data.end());
        return base64_encode(joined);
      }();
      xml += array_start + "format=\"binary\">\n" + encoded + "\n        </DataArray>\n";
      write_tail({});
      break;
    }
    case VtiFormat::AppendedRaw:
    case VtiFormat::AppendedBase64: {
      const bool base64 = options.format == VtiFormat::AppendedBase64;
      xml += array_start + "format=\"appended\" offset=\"0\"/>\n";
      write_tail(base64 ? "base64" : "raw");
      const BinaryArray array = binary_array(volume, options);
      if (base64) {
        out.write(base64_encode(array.header));
        out.write(base64_encode(array.data));
      } else {
        out.write(array.header);
        out.write(array.data);
      }
      out.write(std::string_view("\n  </AppendedData>\n"));
      break;
    }
  }
  out.write(std::string_view("</VTKFile>\n"));
  out.close();
}

}  // namespace penumbra

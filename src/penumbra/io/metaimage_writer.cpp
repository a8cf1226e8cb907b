#include "penumbra/base/error.h"
#include "penumbra/base/memory_budget.h"
#include "penumbra/io/binary_file.h"
#include "penumbra/io/text_parsing.h"
#include "penumbra/io/voxel_output.h"
#include "penumbra/io/volume_writer.h"

#include <fmt/format.h>

namespace penumbra {
namespace {

std::string_view met_type_name(VoxelType type) {
  switch (type) {
    case VoxelType::UInt8: return "MET_UCHAR";
    case VoxelType::Int8: return "MET_CHAR";
    case VoxelType::UInt16: return "MET_USHORT";
    case VoxelType::Int16: return "MET_SHORT";
    case VoxelType::UInt32: return "MET_UINT";
    case VoxelType::Int32: return "MET_INT";
    case VoxelType::Float32: return "MET_FLOAT";
    case VoxelType::Float64: return "MET_DOUBLE";
  }
  return "MET_UCHAR";
}

}  // namespace

void write_metaimage(const std::filesystem::path& path, const Volume& volume, bool compress, std::endian byte_order) {
  const bool attached = to_lower(path.extension().string()) == ".mha";
  const ivec3 d = volume.dims();
  const vec3 s = volume.spacing();
  const vec3 o = volume.origin();
  const bool series = volume.frame_count() > 1;

  // CompressedDataSize precedes the data, so compressed voxels are made in
  // memory first.
  std::vector<std::byte> compressed;
  if (compress) {
    check_memory_budget(fmt::format("compressing {}", display_path(path)), volume.total_bytes());
    compressed = voxel_bytes(volume, 0, volume.frame_count(), byte_order, CompressionFormat::Zlib);
  }

  std::string header = "ObjectType = Image\n";
  header += fmt::format("NDims = {}\n", series ? 4 : 3);
  header += fmt::format("BinaryData = True\nBinaryDataByteOrderMSB = {}\n", byte_order == std::endian::big ? "True" : "False");
  header += fmt::format("CompressedData = {}\n", compress ? "True" : "False");
  if (compress) header += fmt::format("CompressedDataSize = {}\n", compressed.size());
  header += series ? fmt::format("Offset = {} {} {} 0\nElementSpacing = {} {} {} 1\nDimSize = {} {} {} {}\n", o.x, o.y,
                                 o.z, s.x, s.y, s.z, d.x, d.y, d.z, volume.frame_count())
                   : fmt::format("Offset = {} {} {}\nElementSpacing = {} {} {}\nDimSize = {} {} {}\n", o.x, o.y, o.z,
                                 s.x, s.y, s.z, d.x, d.y, d.z);
  header += "ElementNumberOfChannels = 1\n";
  header += fmt::format("ElementType = {}\n", met_type_name(volume.type()));

  std::filesystem::path data_path = path;
  if (attached) {
    header += "ElementDataFile = LOCAL\n";
  } else {
    data_path.replace_extension(compress ? ".zraw" : ".raw");
    header += fmt::format("ElementDataFile = {}\n", data_path.filename().string());
  }

  OutputFile out(path);
  out.write(header);
  if (!attached) {
    out.close();
    OutputFile data(data_path);
    if (compress) {
      data.write(compressed);
    } else {
      write_voxels(data, volume, 0, volume.frame_count(), byte_order, std::nullopt);
    }
    data.close();
    return;
  }
  if (compress) {
    out.write(compressed);
  } else {
    write_voxels(out, volume, 0, volume.frame_count(), byte_order, std::nullopt);
  }
  out.close();
}

}  // namespace penumbra

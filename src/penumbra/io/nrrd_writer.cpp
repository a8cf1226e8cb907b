#include "penumbra/base/error.h"
#include "penumbra/io/voxel_output.h"
#include "penumbra/io/volume_writer.h"

#include <fmt/format.h>

namespace penumbra {
namespace {

std::string_view nrrd_type_name(VoxelType type) {
  switch (type) {
    case VoxelType::UInt8: return "uint8";
    case VoxelType::Int8: return "int8";
    case VoxelType::UInt16: return "uint16";
    case VoxelType::Int16: return "int16";
    case VoxelType::UInt32: return "uint32";
    case VoxelType::Int32: return "int32";
    case VoxelType::Float32: return "float";
    case VoxelType::Float64: return "double";
  }
  return "uint8";
}

}  // namespace

void write_nrrd(const std::filesystem::path& path, const Volume& volume, bool gzip, std::endian byte_order) {
  const ivec3 d = volume.dims();
  const vec3 s = volume.spacing();
  const vec3 o = volume.origin();
  const bool series = volume.frame_count() > 1;
  std::string header = "NRRD0004\n# written by penumbra\n";
  header += fmt::format("type: {}\n", nrrd_type_name(volume.type()));
  header += fmt::format("dimension: {}\n", series ? 4 : 3);
  header += "space dimension: 3\n";
  header += series ? fmt::format("sizes: {} {} {} {}\n", d.x, d.y, d.z, volume.frame_count())
                   : fmt::format("sizes: {} {} {}\n", d.x, d.y, d.z);
  header += fmt::format("space directions: ({},0,0) (0,{},0) (0,0,{}){}\n", s.x, s.y, s.z, series ? " none" : "");
  header += series ? "kinds: domain domain domain list\n" : "kinds: domain domain domain\n";
  header += fmt::format("endian: {}\n", byte_order == std::endian::big ? "big" : "little");
  header += fmt::format("encoding: {}\n", gzip ? "gzip" : "raw");
  header += fmt::format("space origin: ({},{},{})\n\n", o.x, o.y, o.z);

  OutputFile out(path);
  out.write(header);
  write_voxels(out, volume, 0, volume.frame_count(), byte_order,
               gzip ? std::optional(CompressionFormat::Gzip) : std::nullopt);
  out.close();
}

}  // namespace penumbra

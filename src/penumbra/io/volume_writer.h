#pragma once
// Volume writers, so that files made by penumbra (and round-trip tests of the
// readers) need no other tool. Each writes every byte order a reader must
// handle; voxels are streamed in bounded chunks, never copied whole.
#include "penumbra/volume/volume.h"

#include <bit>
#include <filesystem>

namespace penumbra {

// NRRD with an attached header: 3D, or 4D with the frames as the 4th axis
// when the volume has several. Spacing and origin are written as "space
// directions" and "space origin" (NRRD forbids "spacings" beside a space), so
// the file places the volume exactly where it is. encoding gzip or raw.
void write_nrrd(const std::filesystem::path& path, const Volume& volume, bool gzip = false,
                std::endian byte_order = std::endian::little);

// MetaImage: a .mha keeps the voxels after the header (ElementDataFile =
// LOCAL); any other name (.mhd) gets a data file beside it named after the
// header (.raw, or .zraw when compressed). `compress` writes a zlib stream
// (CompressedData = True) per data file.
void write_metaimage(const std::filesystem::path& path, const Volume& volume, bool compress = false,
                     std::endian byte_order = std::endian::little);

enum class VtiFormat { Ascii, Binary, AppendedRaw, AppendedBase64 };

struct VtiWriteOptions {
  VtiFormat format = VtiFormat::AppendedRaw;
  bool compress = false;  // vtkZLibDataCompressor (ignored for Ascii)
  bool header_uint64 = true;  // header_type UInt64, else UInt32
  std::endian byte_order = std::endian::little;
  int frame = 0;  // VTI holds one time step
};

// VTK XML ImageData with one PointData array named "Scalars".
void write_vti(const std::filesystem::path& path, const Volume& volume, const VtiWriteOptions& options = {});

}  // namespace penumbra

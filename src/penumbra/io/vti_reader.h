#pragma once
// VTK XML ImageData (.vti), one piece: WholeExtent, Spacing and Origin (the
// origin of index (0,0,0) is Origin + extent start * Spacing), and the first
// PointData DataArray, or the one PointData's Scalars="..." names. Formats
// "ascii", "binary" (base64, with a UInt32 or UInt64 header_type) and
// "appended" (raw or base64 encoding), each with or without
// compressor="vtkZLibDataCompressor" (VTK's block headers). One component
// per point; 64-bit integer arrays are not supported.
#include "penumbra/volume/volume.h"

#include <filesystem>
#include <memory>

namespace penumbra {

std::shared_ptr<Volume> read_vti(const std::filesystem::path& path);

}  // namespace penumbra

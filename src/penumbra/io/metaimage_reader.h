#pragma once
// MetaImage (ITK's .mhd header + data file, or .mha with the data attached):
// "Key = Value" lines ending with ElementDataFile, which is LOCAL (data follow
// the header), a file name, "LIST [subdim]" followed by file names, or a
// pattern "slice%03d.raw first last step [subdim]". NDims 3 or 4 (4D = time
// series), scalar ElementType MET_CHAR .. MET_DOUBLE (one channel),
// ElementSpacing (or ElementSize), Offset/Origin/Position as the origin,
// BinaryDataByteOrderMSB, HeaderSize (-1 = data at the end of the file) and
// CompressedData (a zlib stream per data file).
#include "penumbra/volume/volume.h"

#include <filesystem>
#include <memory>

namespace penumbra {

std::shared_ptr<Volume> read_metaimage(const std::filesystem::path& path);

}  // namespace penumbra

#pragma once
// Voreen / Inviwo ".dat" text header beside a ".raw" payload:
//   ObjectFileName: nucleon.raw
//   Resolution:     41 41 41
//   SliceThickness: 1 1 1
//   Format:         UCHAR          (CHAR, USHORT, SHORT, UINT, INT, FLOAT, DOUBLE,
//                                   or Inviwo's UINT8 .. FLOAT64)
//   ByteOrder:      LittleEndian   (optional; Inviwo)
//   ObjectModel:    I              (optional; only scalar "I" is supported)
// Keys are case-insensitive; unknown keys (TaggedFileName, GridType, ...) are
// ignored. An optional "ByteOffset" skips a header inside the .raw file.
#include "penumbra/volume/volume.h"

#include <filesystem>
#include <memory>

namespace penumbra {

std::shared_ptr<Volume> read_dat(const std::filesystem::path& path);

}  // namespace penumbra

#pragma once
// Reads a volume file, choosing the format by extension (case-insensitive):
// .nrrd .nhdr (NRRD), .mhd .mha (MetaImage), .nii .nii.gz (NIfTI-1),
// .vti (VTK XML ImageData), .dat (Voreen/Inviwo header of a .raw file).
// A .raw file is read through the .dat or .nhdr of the same name beside it.
// Every reader sets Volume::source to the path and throws IoError (or
// OutOfMemoryBudget) for anything it cannot read; none allocates before
// checking sizes against the files and the memory budget.
#include "penumbra/volume/volume.h"

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace penumbra {

std::shared_ptr<Volume> read_volume(const std::filesystem::path& path);

// ".nrrd", ".nhdr", ... in the order listed above.
const std::vector<std::string>& supported_volume_extensions();

}  // namespace penumbra

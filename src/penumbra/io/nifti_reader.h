#pragma once
// NIfTI-1 single files (.nii, and .nii.gz compressed as a whole): the 348-byte
// header in either byte order (detected from sizeof_hdr), datatypes uint8,
// int8, int16, uint16, int32, uint32, float32 and float64, dim[1..4] (4D =
// time series), pixdim[1..3] as the spacing and vox_offset. When scl_slope is
// non-zero and not the identity (1, 0), values are scaled to float32.
// The origin comes from the sform (or else the qform) only when that maps
// index to world by a translation and positive scales: penumbra's
// world_from_index has no rotation or flip, so for any other orientation the
// volume stays centred rather than being placed at a misleading offset.
#include "penumbra/volume/volume.h"

#include <filesystem>
#include <memory>

namespace penumbra {

std::shared_ptr<Volume> read_nifti(const std::filesystem::path& path);

}  // namespace penumbra

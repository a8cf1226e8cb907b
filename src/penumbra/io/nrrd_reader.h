#pragma once
// NRRD (teem.sourceforge.net/nrrd/format.html): attached (.nrrd) and detached
// (.nhdr) headers; encodings raw and gzip; little and big endian; all scalar
// types and their aliases (64-bit integers excepted); 3D volumes and 4D time
// series (the 4th axis is frames); one data file, "LIST" or a printf pattern
// ("data file: name_%03d.raw.gz 1 91 10 3"), each with "line skip" and
// "byte skip"; spacing from "spacings" or the lengths of "space directions";
// origin from "space origin" when present (otherwise the volume stays centred).
#include "penumbra/volume/volume.h"

#include <filesystem>
#include <memory>

namespace penumbra {

std::shared_ptr<Volume> read_nrrd(const std::filesystem::path& path);

}  // namespace penumbra

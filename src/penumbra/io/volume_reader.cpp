#include "penumbra/io/volume_reader.h"

#include "penumbra/base/error.h"
#include "penumbra/io/binary_file.h"
#include "penumbra/io/dat_reader.h"
#include "penumbra/io/metaimage_reader.h"
#include "penumbra/io/nifti_reader.h"
#include "penumbra/io/nrrd_reader.h"
#include "penumbra/io/text_parsing.h"
#include "penumbra/io/vti_reader.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <system_error>

namespace penumbra {

const std::vector<std::string>& supported_volume_extensions() {
  static const std::vector<std::string> kExtensions = {".nrrd", ".nhdr", ".mhd", ".mha", ".nii",
                                                       ".nii.gz", ".vti", ".dat"};
  return kExtensions;
}

std::shared_ptr<Volume> read_volume(const std::filesystem::path& path) {
  const std::string name = to_lower(path.filename().string());
  const auto has = [&](std::string_view extension) { return name.size() > extension.size() && name.ends_with(extension); };
  if (has(".nrrd") || has(".nhdr")) return read_nrrd(path);
  if (has(".mhd") || has(".mha")) return read_metaimage(path);
  if (has(".nii") || has(".nii.gz")) return read_nifti(path);
  if (has(".vti")) return read_vti(path);
  if (has(".dat")) return read_dat(path);
  if (has(".raw")) {
    // A bare .raw has no layout; use the header written beside it.
    for (const char* header : {".dat", ".nhdr"}) {
      std::filesystem::path candidate = path;
      candidate.replace_extension(header);
      std::error_code ec;
      if (std::filesystem::is_regular_file(candidate, ec)) return read_volume(candidate);
    }
    throw IoError(display_path(path), "a .raw file has no dimensions or type; open the .dat or .nhdr header that "
                                      "describes it");
  }
  throw IoError(display_path(path),
                fmt::format("unknown volume file extension; supported: {}, and .raw with a .dat or .nhdr of the same "
                            "name beside it",
                            fmt::join(supported_volume_extensions(), ", ")));
}

}  // namespace penumbra

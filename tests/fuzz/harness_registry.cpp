// The list of harnesses, for the regression test (the fuzz targets name
// theirs at build time and link only what it needs).
#include "harness.h"

#include <fmt/format.h>

#include <stdexcept>

namespace penumbra::fuzz {

const std::vector<Harness>& harnesses() {
  static const std::vector<Harness> kHarnesses = {
      {"nrrd", fuzz_nrrd, "read_volume on a .nrrd (attached or detached data, every encoding)"},
      {"metaimage", fuzz_metaimage, "read_volume on a .mha (LOCAL, a data file, LIST or a pattern)"},
      {"nifti", fuzz_nifti, "read_volume on a .nii, or a .nii.gz when the input is gzip"},
      {"vti", fuzz_vti, "read_volume on a .vti (ascii, base64, appended, zlib)"},
      {"dat", fuzz_dat, "read_volume on a .dat header and on its .raw"},
      {"scene", fuzz_scene, "parse_scene with files, then prepare and render 8x8 with its technique"},
      {"obj", fuzz_obj, "read_mesh on an .obj, then validate()"},
      {"ply", fuzz_ply, "read_mesh on a .ply, then validate()"},
      {"preset", fuzz_preset, "ParaView presets: JSON text, or an .xml file when the input starts with '<'"},
      {"server", fuzz_server, "server requests: scene PUT, frame POST or GET query, through send_exception"},
  };
  return kHarnesses;
}

const Harness& find_harness(std::string_view name) {
  for (const Harness& h : harnesses()) {
    if (h.name == name) return h;
  }
  throw std::invalid_argument(fmt::format("no fuzz harness named '{}'", name));
}

}  // namespace penumbra::fuzz

// The volume readers: the input becomes a file of the reader's extension in
// the fixture folder, where the companions a header may name (data.raw,
// data.raw.gz, data.zraw, slice000.raw ...) lie beside it. The volume that
// comes back is checked for consistency: the reader's promise is a volume
// whose voxels and value range can be used as they are.
#include "harness.h"

#include "penumbra/io/volume_reader.h"

#include <fmt/format.h>

#include <cmath>

namespace penumbra::fuzz {
namespace {

void check_volume(const Volume& v, std::string_view target) {
  const ivec3 d = v.dims();
  const bool ok = d.x > 0 && d.y > 0 && d.z > 0 && v.frame_count() > 0 &&
                  v.voxel_count() == std::uint64_t(d.x) * std::uint64_t(d.y) * std::uint64_t(d.z) &&
                  std::isfinite(v.spacing().x) && std::isfinite(v.spacing().y) && std::isfinite(v.spacing().z) &&
                  v.spacing().x > 0.0f && v.spacing().y > 0.0f && v.spacing().z > 0.0f &&
                  std::isfinite(v.origin().x) && std::isfinite(v.origin().y) && std::isfinite(v.origin().z);
  if (!ok) {
    throw HarnessFailure(fmt::format("fuzz_{}: inconsistent volume {}x{}x{}, {} frames, spacing {} {} {}", target,
                                     d.x, d.y, d.z, v.frame_count(), v.spacing().x, v.spacing().y, v.spacing().z));
  }
  // Touch every voxel the way techniques do (the value range scans them all).
  for (int f = 0; f < v.frame_count(); ++f) (void)v.value_range(f);
}

void read_as(std::string_view file_name, Input input, std::string_view target) {
  const auto volume = read_volume(write_input(file_name, input));
  check_volume(*volume, target);
}

bool is_gzip(Input input) { return input.size() >= 2 && input[0] == 0x1f && input[1] == 0x8b; }

}  // namespace

void fuzz_nrrd(Input input) { read_as("input.nrrd", input, "nrrd"); }

void fuzz_metaimage(Input input) { read_as("input.mha", input, "metaimage"); }

void fuzz_nifti(Input input) { read_as(is_gzip(input) ? "input.nii.gz" : "input.nii", input, "nifti"); }

void fuzz_vti(Input input) { read_as("input.vti", input, "vti"); }

void fuzz_dat(Input input) {
  read_as("input.dat", input, "dat");
  // A bare .raw is read through the .dat beside it.
  const auto volume = read_volume(fixture_dir() / "input.raw");
  check_volume(*volume, "dat");
}

}  // namespace penumbra::fuzz

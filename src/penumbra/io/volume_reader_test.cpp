#include "penumbra/io/volume_reader.h"

#include "penumbra/io/io_test_support.h"
#include "penumbra/io/volume_writer.h"

#include <gtest/gtest.h>

namespace penumbra {
namespace {

using test::TempDir;

TEST(VolumeReader, ChoosesTheReaderByExtensionIgnoringCase) {
  TempDir dir;
  const auto volume = test::make_volume(ivec3(4, 3, 2), VoxelType::Int16);
  write_nrrd(dir / "A.NRRD", *volume);
  write_metaimage(dir / "b.mha", *volume);
  write_metaimage(dir / "c.MHD", *volume, true);
  write_vti(dir / "d.vti", *volume);
  for (const char* name : {"A.NRRD", "b.mha", "c.MHD", "d.vti"}) {
    SCOPED_TRACE(name);
    const auto back = read_volume(dir / name);
    test::expect_same_voxels(*volume, *back);
    EXPECT_EQ(back->source(), (dir / name).string());
  }
}

TEST(VolumeReader, ReadsARawFileThroughTheDatHeaderBesideIt) {
  TempDir dir;
  const auto volume = test::make_volume(ivec3(4, 3, 2), VoxelType::UInt8);
  test::write_file(dir / "v.raw", test::voxel_file_bytes(*volume, std::endian::little));
  test::write_file(dir / "v.dat", "ObjectFileName: v.raw\nResolution: 4 3 2\nFormat: UCHAR\n");
  test::expect_same_voxels(*volume, *read_volume(dir / "v.dat"));
  test::expect_same_voxels(*volume, *read_volume(dir / "v.raw"));
  test::write_file(dir / "lonely.raw", "x");
  test::expect_io_error([&] { read_volume(dir / "lonely.raw"); }, "open the .dat or .nhdr");
}

TEST(VolumeReader, UnknownExtensionListsTheSupportedOnes) {
  TempDir dir;
  test::write_file(dir / "v.tiff", "II*");
  test::expect_io_error([&] { read_volume(dir / "v.tiff"); },
                        "unknown volume file extension; supported: .nrrd, .nhdr, .mhd, .mha, .nii, .nii.gz, .vti, .dat, and "
                        ".raw with a .dat or .nhdr of the same name beside it");
  EXPECT_EQ(supported_volume_extensions().size(), 8u);
  // A file without an extension gets the same whole list.
  test::write_file(dir / "noextension", "NRRD0004\n");
  test::expect_io_error([&] { read_volume(dir / "noextension"); }, ".vti, .dat, and .raw with a .dat or .nhdr");
}

TEST(VolumeReader, MissingFilesAndFoldersGiveIoError) {
  TempDir dir;
  test::expect_io_error([&] { read_volume(dir / "absent.nrrd"); }, "file not found");
  std::filesystem::create_directory(dir / "folder.nrrd");
  test::expect_io_error([&] { read_volume(dir / "folder.nrrd"); }, "not a regular file");
  test::expect_io_error([&] { read_volume(dir / "absent.nii.gz"); }, "file not found");
  test::expect_io_error([&] { read_volume(dir / "absent.vti"); }, "file not found");
}

}  // namespace
}  // namespace penumbra

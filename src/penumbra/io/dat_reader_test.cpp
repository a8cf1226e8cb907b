#include "penumbra/io/dat_reader.h"

#include "penumbra/io/io_test_support.h"

#include <gtest/gtest.h>

namespace penumbra {
namespace {

using test::TempDir;

TEST(DatReader, ReadsVoreenHeaderWithRawFile) {
  TempDir dir;
  const auto expected = test::make_volume(ivec3(6, 5, 4), VoxelType::UInt8);
  test::write_file(dir / "nucleon.raw", test::voxel_file_bytes(*expected, std::endian::little));
  test::write_file(dir / "nucleon.dat",
                   "ObjectFileName:\tnucleon.raw\nTaggedFileName: ---\nResolution: 6 5 4\n"
                   "SliceThickness: 1 1.5 2\nFormat: UCHAR\nNbrTags: 0\nObjectType: TEXTURE_VOLUME_OBJECT\n"
                   "ObjectModel: I\nGridType: EQUIDISTANT\n");
  const auto volume = read_dat(dir / "nucleon.dat");
  test::expect_same_voxels(*expected, *volume);
  EXPECT_EQ(volume->spacing(), vec3(1.0f, 1.5f, 2.0f));
  EXPECT_EQ(volume->source(), (dir / "nucleon.dat").string());
}

TEST(DatReader, ReadsInviwoFormatsAndByteOrder) {
  TempDir dir;
  const std::vector<std::pair<std::string, VoxelType>> formats = {
      {"USHORT", VoxelType::UInt16}, {"SHORT", VoxelType::Int16},    {"FLOAT", VoxelType::Float32},
      {"DOUBLE", VoxelType::Float64}, {"UINT32", VoxelType::UInt32}, {"char", VoxelType::Int8},
  };
  for (const auto& [format, type] : formats) {
    for (std::endian order : {std::endian::little, std::endian::big}) {
      const auto expected = test::make_volume(ivec3(3, 4, 2), type);
      test::write_file(dir / "v.raw", test::voxel_file_bytes(*expected, order));
      test::write_file(dir / "v.dat", "rawfile: v.raw\nresolution: 3 4 2\nformat: " + format + "\nByteOrder: " +
                                          (order == std::endian::big ? "BigEndian" : "LittleEndian") + "\n");
      SCOPED_TRACE(format);
      test::expect_same_voxels(*expected, *read_dat(dir / "v.dat"));
    }
  }
}

TEST(DatReader, MalformedHeadersAndPayloadsGiveIoError) {
  TempDir dir;
  test::write_file(dir / "v.raw", std::vector<std::byte>(24, std::byte{3}));
  const auto expect = [&](const std::string& header, std::string_view fragment) {
    test::write_file(dir / "v.dat", header);
    test::expect_io_error([&] { read_dat(dir / "v.dat"); }, fragment);
  };
  expect("Resolution: 2 3 4\nFormat: UCHAR\n", "'ObjectFileName' is missing");
  expect("ObjectFileName: v.raw\nResolution: 2 3\nFormat: UCHAR\n", "'Resolution' should be three integers");
  expect("ObjectFileName: v.raw\nResolution: 2 -3 4\nFormat: UCHAR\n", "entry 2 is -3");
  expect("ObjectFileName: v.raw\nResolution: 2 3 4\nFormat: HALF\n", "Format 'HALF' is not supported");
  expect("ObjectFileName: v.raw\nResolution: 2 3 4\nFormat: UCHAR\nObjectModel: RGBA\n", "scalar volumes");
  expect("ObjectFileName: v.raw\nResolution: 2 3 5\nFormat: UCHAR\n", "truncated");
  expect("ObjectFileName: gone.raw\nResolution: 2 3 4\nFormat: UCHAR\n", "file not found");
  expect("ObjectFileName: v.raw\nResolution: 2 3 4\nFormat: UCHAR\nSliceThickness: 1 0 1\n", "must be positive");
  expect("just some text\n", "not 'Key: value'");
}

}  // namespace
}  // namespace penumbra

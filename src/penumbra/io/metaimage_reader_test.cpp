#include "penumbra/io/metaimage_reader.h"

#include "penumbra/io/io_test_support.h"

#include <gtest/gtest.h>

#include <fmt/format.h>

namespace penumbra {
namespace {

using test::TempDir;

TEST(MetaImageReader, ReadsDetachedHeaderWithSpacingOffsetAndByteOrder) {
  TempDir dir;
  for (std::endian order : {std::endian::little, std::endian::big}) {
    const auto expected = test::make_volume(ivec3(4, 3, 5), VoxelType::Int16);
    test::write_file(dir / "ct.raw", test::voxel_file_bytes(*expected, order));
    // Keys in an unusual order and case, as hand-written headers have them.
    test::write_file(dir / "ct.mhd",
                     fmt::format("ObjectType = Image\nelementtype = MET_SHORT\nNDims = 3\n"
                                 "BinaryDataByteOrderMSB = {}\nDimSize = 4 3 5\nElementSpacing = 0.5 0.5 2.5\n"
                                 "Offset = -1 2 3.5\nTransformMatrix = 1 0 0 0 1 0 0 0 1\n"
                                 "ElementDataFile = ct.raw\n",
                                 order == std::endian::big ? "True" : "False"));
    const auto volume = read_metaimage(dir / "ct.mhd");
    test::expect_same_voxels(*expected, *volume);
    EXPECT_EQ(volume->spacing(), vec3(0.5f, 0.5f, 2.5f));
    EXPECT_EQ(volume->origin(), vec3(-1.0f, 2.0f, 3.5f));
  }
}

TEST(MetaImageReader, ReadsLocalDataPlainAndZlibCompressed) {
  TempDir dir;
  const auto expected = test::make_volume(ivec3(7, 3, 2), VoxelType::Float32, 2);
  const std::vector<std::byte> voxels = test::voxel_file_bytes(*expected, std::endian::little);
  const std::string header =
      "NDims = 4\nDimSize = 7 3 2 2\nElementType = MET_FLOAT\nElementSize = 2 2 2 1\nHeaderSize = 0\n";
  test::write_file(dir / "plain.mha", test::concat({test::text_bytes(header + "ElementDataFile = LOCAL\n"), voxels}));
  const auto plain = read_metaimage(dir / "plain.mha");
  test::expect_same_voxels(*expected, *plain);
  EXPECT_EQ(plain->spacing(), vec3(2.0f));

  const std::vector<std::byte> packed = deflate_bytes(voxels, CompressionFormat::Zlib);
  test::write_file(dir / "packed.mha",
                   test::concat({test::text_bytes(header + fmt::format("CompressedData = True\nCompressedDataSize = "
                                                                        "{}\nElementDataFile = LOCAL\n",
                                                                        packed.size())),
                                 packed}));
  test::expect_same_voxels(*expected, *read_metaimage(dir / "packed.mha"));
}

TEST(MetaImageReader, ReadsListAndPatternDataFiles) {
  TempDir dir;
  const auto expected = test::make_volume(ivec3(2, 2, 3), VoxelType::UInt8);
  const std::vector<std::byte> voxels = test::voxel_file_bytes(*expected, std::endian::little);
  for (int z = 0; z < 3; ++z) test::write_file(dir / fmt::format("s{:02d}.raw", z), std::span(voxels).subspan(4u * z, 4));
  test::write_file(dir / "pattern.mhd",
                   "NDims = 3\nDimSize = 2 2 3\nElementType = MET_UCHAR\nElementDataFile = s%02d.raw 0 2 1\n");
  test::expect_same_voxels(*expected, *read_metaimage(dir / "pattern.mhd"));
  test::write_file(dir / "list.mhd",
                   "NDims = 3\nDimSize = 2 2 3\nElementType = MET_UCHAR\nElementDataFile = LIST\ns00.raw\ns01.raw\n"
                   "s02.raw\n");
  test::expect_same_voxels(*expected, *read_metaimage(dir / "list.mhd"));
}

TEST(MetaImageReader, MalformedHeadersAndPayloadsGiveIoError) {
  TempDir dir;
  test::write_file(dir / "v.raw", std::vector<std::byte>(24, std::byte{3}));
  const auto expect = [&](const std::string& header, std::string_view fragment) {
    test::write_file(dir / "v.mhd", header);
    test::expect_io_error([&] { read_metaimage(dir / "v.mhd"); }, fragment);
  };
  const std::string type = "ElementType = MET_UCHAR\n";
  expect("NDims = 3\nDimSize = 2 3\n" + type + "ElementDataFile = v.raw\n", "DimSize has 2 entries but NDims is 3");
  expect("NDims = 2\nDimSize = 2 3\n" + type + "ElementDataFile = v.raw\n", "NDims is '2'");
  expect("NDims = 3\nDimSize = 2 0 4\n" + type + "ElementDataFile = v.raw\n", "entry 2 is 0");
  expect("NDims = 3\nDimSize = 2 3 4\nElementType = MET_LONG_LONG\nElementDataFile = v.raw\n",
         "ElementType 'MET_LONG_LONG' is not supported");
  expect("NDims = 3\nDimSize = 2 3 4\nElementNumberOfChannels = 3\n" + type + "ElementDataFile = v.raw\n",
         "ElementNumberOfChannels is 3");
  expect("NDims = 3\nDimSize = 2 3 5\n" + type + "ElementDataFile = v.raw\n", "truncated");
  expect("NDims = 3\nDimSize = 2 3 4\n" + type + "CompressedData = True\nElementDataFile = v.raw\n",
         "corrupt compressed data");
  expect("NDims = 3\nDimSize = 2 3 4\n" + type + "ElementDataFile = missing.raw\n", "file not found");
  expect("NDims = 3\nDimSize = 2 3 4\n" + type, "'elementdatafile' is missing");
  expect("NDims = 3\nDimSize = 2 3 4\n" + type + "BinaryDataByteOrderMSB = maybe\nElementDataFile = v.raw\n",
         "True or False");
}

}  // namespace
}  // namespace penumbra

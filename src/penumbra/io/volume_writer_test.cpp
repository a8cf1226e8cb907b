// Round trips through each writer and its reader, for every voxel type and
// both byte orders, with and without compression.
#include "penumbra/io/volume_writer.h"

#include "penumbra/io/io_test_support.h"
#include "penumbra/io/metaimage_reader.h"
#include "penumbra/io/nrrd_reader.h"
#include "penumbra/io/vti_reader.h"

#include <gtest/gtest.h>

namespace penumbra {
namespace {

using test::TempDir;

constexpr VoxelType kAllTypes[] = {VoxelType::UInt8,  VoxelType::Int8,  VoxelType::UInt16,  VoxelType::Int16,
                                   VoxelType::UInt32, VoxelType::Int32, VoxelType::Float32, VoxelType::Float64};

std::shared_ptr<Volume> placed_volume(VoxelType type, int frames) {
  auto volume = test::make_volume(ivec3(7, 5, 3), type, frames);
  volume->set_spacing(vec3(0.25f, 1.0f, 3.5f));
  volume->set_origin(vec3(-1.5f, 0.125f, 1e3f));
  return volume;
}

// Writing to a new file rather than truncating the last one keeps ext4 from
// flushing every rewrite (auto_da_alloc), which made this test slow.
std::filesystem::path fresh(const std::filesystem::path& path) {
  std::error_code ec;
  std::filesystem::remove(path, ec);
  return path;
}

void expect_same_volume(const Volume& expected, const Volume& actual) {
  test::expect_same_voxels(expected, actual);
  EXPECT_EQ(expected.spacing(), actual.spacing());
  EXPECT_EQ(expected.origin(), actual.origin());
}

TEST(VolumeWriter, NrrdRoundTripsEveryTypeByteOrderAndEncoding) {
  TempDir dir;
  for (VoxelType type : kAllTypes) {
    for (std::endian order : {std::endian::little, std::endian::big}) {
      for (bool gzip : {false, true}) {
        SCOPED_TRACE(testing::Message() << to_string(type) << (order == std::endian::big ? " big" : " little")
                                        << (gzip ? " gzip" : " raw"));
        const auto volume = placed_volume(type, 1);
        write_nrrd(fresh(dir / "v.nrrd"), *volume, gzip, order);
        const auto back = read_nrrd(dir / "v.nrrd");
        expect_same_volume(*volume, *back);
        EXPECT_EQ(back->source(), (dir / "v.nrrd").string());
      }
    }
  }
}

TEST(VolumeWriter, NrrdWritesSeriesAsFourDimensions) {
  TempDir dir;
  const auto series = placed_volume(VoxelType::Float32, 4);
  write_nrrd(dir / "series.nrrd", *series, true);
  expect_same_volume(*series, *read_nrrd(dir / "series.nrrd"));
}

TEST(VolumeWriter, MetaImageRoundTripsAttachedAndDetachedCompressedOrNot) {
  TempDir dir;
  for (VoxelType type : kAllTypes) {
    for (std::endian order : {std::endian::little, std::endian::big}) {
      for (bool compress : {false, true}) {
        for (const char* name : {"v.mha", "v.mhd"}) {
          SCOPED_TRACE(testing::Message() << to_string(type) << " " << name << (compress ? " zlib" : " raw")
                                          << (order == std::endian::big ? " big" : " little"));
          const auto volume = placed_volume(type, type == VoxelType::Int16 ? 2 : 1);
          write_metaimage(fresh(dir / name), *volume, compress, order);
          expect_same_volume(*volume, *read_metaimage(dir / name));
        }
      }
    }
  }
  EXPECT_TRUE(std::filesystem::exists(dir / "v.zraw"));
  EXPECT_TRUE(std::filesystem::exists(dir / "v.raw"));
}

TEST(VolumeWriter, VtiRoundTripsEveryFormatCompressionAndHeaderType) {
  TempDir dir;
  for (VoxelType type : kAllTypes) {
    for (VtiFormat format : {VtiFormat::Ascii, VtiFormat::Binary, VtiFormat::AppendedRaw, VtiFormat::AppendedBase64}) {
      for (bool compress : {false, true}) {
        for (bool uint64 : {false, true}) {
          const std::endian order = uint64 ? std::endian::big : std::endian::little;
          SCOPED_TRACE(testing::Message() << to_string(type) << " format " << int(format) << (compress ? " zlib" : "")
                                          << (uint64 ? " UInt64 big" : " UInt32 little"));
          const auto volume = placed_volume(type, 1);
          write_vti(fresh(dir / "v.vti"), *volume, {format, compress, uint64, order});
          expect_same_volume(*volume, *read_vti(dir / "v.vti"));
        }
      }
    }
  }
}

TEST(VolumeWriter, VtiCompressesVolumesLargerThanOneBlockAndWritesOneFrame) {
  TempDir dir;
  auto series = test::make_volume(ivec3(64, 40, 9), VoxelType::UInt16, 2);  // 46080 bytes: two zlib blocks
  for (VtiFormat format : {VtiFormat::Binary, VtiFormat::AppendedRaw, VtiFormat::AppendedBase64}) {
    VtiWriteOptions options;
    options.format = format;
    options.compress = true;
    options.frame = 1;
    write_vti(fresh(dir / "big.vti"), *series, options);
    const auto back = read_vti(dir / "big.vti");
    ASSERT_EQ(back->frame_count(), 1);
    EXPECT_EQ(0, std::memcmp(back->frame_data(0), series->frame_data(1), series->frame_bytes()));
  }
  VtiWriteOptions missing;
  missing.frame = 2;
  EXPECT_THROW(write_vti(dir / "big.vti", *series, missing), InvalidArgument);
}

TEST(VolumeWriter, UnwritablePathGivesIoError) {
  const auto volume = test::make_volume(ivec3(2), VoxelType::UInt8);
  const std::filesystem::path nowhere = "/nonexistent-dir-penumbra/v.nrrd";
  test::expect_io_error([&] { write_nrrd(nowhere, *volume); }, "cannot open the file for writing");
  test::expect_io_error([&] { write_metaimage("/nonexistent-dir-penumbra/v.mha", *volume); }, "cannot open");
  test::expect_io_error([&] { write_vti("/nonexistent-dir-penumbra/v.vti", *volume); }, "cannot open");
}

}  // namespace
}  // namespace penumbra

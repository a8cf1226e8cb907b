#include "penumbra/io/nifti_reader.h"

#include "penumbra/io/io_test_support.h"

#include <cmath>
#include <gtest/gtest.h>


namespace penumbra {
namespace {

using test::NiftiHeader;
using test::TempDir;

TEST(NiftiReader, ReadsBothByteOrdersAndEveryDatatype) {
  const std::vector<std::pair<std::int16_t, VoxelType>> types = {
      {2, VoxelType::UInt8},   {256, VoxelType::Int8},    {4, VoxelType::Int16},    {512, VoxelType::UInt16},
      {8, VoxelType::Int32},   {768, VoxelType::UInt32},  {16, VoxelType::Float32}, {64, VoxelType::Float64},
  };
  TempDir dir;
  for (const auto& [code, type] : types) {
    for (std::endian order : {std::endian::little, std::endian::big}) {
      const auto expected = test::make_volume(ivec3(5, 3, 2), type);
      const auto path = dir / "v.nii";
      test::write_file(path, NiftiHeader(order).dims({5, 3, 2}).datatype(code).pixdim(0.5f, 1.0f, 2.0f)
                                 .file(test::voxel_file_bytes(*expected, order)));
      SCOPED_TRACE(testing::Message() << "datatype " << code << (order == std::endian::big ? " big" : " little"));
      const auto volume = read_nifti(path);
      test::expect_same_voxels(*expected, *volume);
      EXPECT_EQ(volume->spacing(), vec3(0.5f, 1.0f, 2.0f));
      EXPECT_FLOAT_EQ(volume->world_box().lower.x, -1.0f);  // no sform/qform: centred
    }
  }
}

TEST(NiftiReader, ReadsGzippedFourDimensionalFilesAndAxisAlignedSformOrigin) {
  TempDir dir;
  const auto expected = test::make_volume(ivec3(4, 4, 3), VoxelType::Int16, 3);
  const auto path = dir / "series.nii.gz";
  test::write_file(path, test::gzip(NiftiHeader(std::endian::little)
                                        .dims({4, 4, 3, 3})
                                        .datatype(4)
                                        .pixdim(1, 1, 1)
                                        .sform({1, 0, 0, -90, 0, 1, 0, -125, 0, 0, 1, -71})
                                        .file(test::voxel_file_bytes(*expected, std::endian::little))));
  const auto volume = read_nifti(path);
  EXPECT_EQ(volume->frame_count(), 3);
  test::expect_same_voxels(*expected, *volume);
  EXPECT_EQ(volume->origin(), vec3(-90.0f, -125.0f, -71.0f));

  // A flipped sform cannot be expressed by origin + spacing: stay centred.
  test::write_file(path, test::gzip(NiftiHeader(std::endian::little)
                                        .dims({4, 4, 3})
                                        .datatype(4)
                                        .sform({-1, 0, 0, 90, 0, 1, 0, -125, 0, 0, 1, -71})
                                        .file(test::voxel_file_bytes(*test::make_volume(ivec3(4, 4, 3),
                                                                                       VoxelType::Int16),
                                                                     std::endian::little))));
  EXPECT_FLOAT_EQ(read_nifti(path)->world_box().lower.x, -1.5f);
}

TEST(NiftiReader, AppliesSlopeAndInterceptAsFloat) {
  TempDir dir;
  const auto raw = test::make_volume(ivec3(3, 3, 3), VoxelType::Int16);
  const auto path = dir / "scaled.nii";
  test::write_file(path, NiftiHeader(std::endian::big).dims({3, 3, 3}).datatype(4).scaling(0.5f, -10.0f)
                             .file(test::voxel_file_bytes(*raw, std::endian::big)));
  const auto volume = read_nifti(path);
  ASSERT_EQ(volume->type(), VoxelType::Float32);
  for (int i = 0; i < 27; ++i) {
    const ivec3 index(i % 3, (i / 3) % 3, i / 9);
    EXPECT_FLOAT_EQ(volume->voxel(0, index), raw->voxel(0, index) * 0.5f - 10.0f);
  }
  // The identity scaling keeps the stored type.
  test::write_file(path, NiftiHeader(std::endian::little).dims({3, 3, 3}).datatype(4).scaling(1.0f, 0.0f)
                             .file(test::voxel_file_bytes(*raw, std::endian::little)));
  EXPECT_EQ(read_nifti(path)->type(), VoxelType::Int16);
}

TEST(NiftiReader, MalformedFilesGiveIoError) {
  TempDir dir;
  const auto path = dir / "bad.nii";
  const std::vector<std::byte> voxels(60, std::byte{1});
  const auto expect = [&](const std::vector<std::byte>& bytes, std::string_view fragment) {
    test::write_file(path, bytes);
    test::expect_io_error([&] { read_nifti(path); }, fragment);
  };
  const auto good = [] { return NiftiHeader(std::endian::little).dims({3, 4, 5}).datatype(2); };
  expect(good().put<std::int32_t>(0, 347).file(voxels), "sizeof_hdr is 347");
  expect(good().put<std::int32_t>(0, 540).file(voxels), "NIfTI-2");
  expect(good().datatype(128).file(voxels), "datatype 128 is not supported");
  expect(NiftiHeader(std::endian::little).dims({3, -4, 5}).datatype(2).file(voxels), "dim[2] is -4");
  expect(NiftiHeader(std::endian::little).dims({3, 4}).datatype(2).file(voxels), "dim[0] is 2");
  expect(good().file(std::span(voxels).first(59)), "truncated");
  expect(good().put<float>(108, 100.0f).file(voxels), "vox_offset is 100");
  std::vector<std::byte> pair = good().file(voxels);
  std::memcpy(pair.data() + 344, "ni1\0", 4);
  expect(pair, ".hdr/.img pair");
  expect(std::vector<std::byte>(100, std::byte{0}), "truncated");
  test::write_file(dir / "bad.nii.gz", std::vector<std::byte>(400, std::byte{7}));
  test::expect_io_error([&] { read_nifti(dir / "bad.nii.gz"); }, "corrupt compressed data");
}

// pixdim 0 and NaN are "unknown" in the wild (unit spacing), a negative one
// keeps its magnitude, an infinite one is an error.
TEST(NiftiReader, PixdimUnknownNegativeAndInfinite) {
  TempDir dir;
  const auto path = dir / "p.nii";
  const std::vector<std::byte> voxels(60, std::byte{1});
  const auto header = [] { return NiftiHeader(std::endian::little).dims({3, 4, 5}).datatype(2); };
  test::write_file(path, header().pixdim(0.0f, std::nanf(""), -2.5f).file(voxels));
  EXPECT_EQ(read_nifti(path)->spacing(), vec3(1.0f, 1.0f, 2.5f));
  test::write_file(path, header().pixdim(1.0f, INFINITY, 1.0f).file(voxels));
  test::expect_io_error([&] { read_nifti(path); }, "pixdim[2] is inf");
  // Finite, but the centred box of 5 voxels of 2.5e38 would reach infinity
  // (found by fuzz_nifti).
  test::write_file(path, header().pixdim(1.0f, 1.0f, 2.5e38f).file(voxels));
  test::expect_io_error([&] { read_nifti(path); }, "the volume's box reaches");
}

}  // namespace
}  // namespace penumbra

#include "penumbra/io/nrrd_reader.h"

#include "penumbra/base/memory_budget.h"
#include "penumbra/io/io_test_support.h"

#include <gtest/gtest.h>

#include <fmt/format.h>

namespace penumbra {
namespace {

using test::TempDir;

// An attached NRRD: header lines, a blank line, then the payload.
void write_attached(const std::filesystem::path& path, const std::string& header, std::span<const std::byte> data) {
  test::write_file(path, test::concat({test::text_bytes("NRRD0004\n" + header + "\n"), data}));
}

TEST(NrrdReader, ReadsEveryTypeAliasFromAnAttachedRawFile) {
  const std::vector<std::pair<std::string, VoxelType>> aliases = {
      {"signed char", VoxelType::Int8},      {"int8_t", VoxelType::Int8},      {"uchar", VoxelType::UInt8},
      {"unsigned char", VoxelType::UInt8},   {"uint8_t", VoxelType::UInt8},    {"short", VoxelType::Int16},
      {"signed short int", VoxelType::Int16}, {"int16", VoxelType::Int16},     {"ushort", VoxelType::UInt16},
      {"unsigned  short", VoxelType::UInt16}, {"uint16_t", VoxelType::UInt16}, {"int", VoxelType::Int32},
      {"signed int", VoxelType::Int32},      {"int32_t", VoxelType::Int32},    {"uint", VoxelType::UInt32},
      {"unsigned int", VoxelType::UInt32},   {"float", VoxelType::Float32},    {"double", VoxelType::Float64},
  };
  TempDir dir;
  for (const auto& [alias, type] : aliases) {
    const auto expected = test::make_volume(ivec3(5, 4, 3), type);
    const auto path = dir / "alias.nrrd";
    write_attached(path,
                   fmt::format("# comment\ntype: {}\ndimension: 3\nsizes: 5 4 3\nendian: little\nencoding: raw\n"
                               "key:=value with: colon\n",
                               alias),
                   test::voxel_file_bytes(*expected, std::endian::little));
    const auto volume = read_nrrd(path);
    SCOPED_TRACE(alias);
    test::expect_same_voxels(*expected, *volume);
    EXPECT_EQ(volume->source(), path.string());
    // No origin given: the volume stays centred.
    EXPECT_FLOAT_EQ(volume->world_box().lower.x, -2.0f);
  }
}

TEST(NrrdReader, SwapsBigEndianData) {
  TempDir dir;
  for (VoxelType type : {VoxelType::Int16, VoxelType::UInt32, VoxelType::Float32, VoxelType::Float64}) {
    const auto expected = test::make_volume(ivec3(3, 2, 2), type);
    const auto path = dir / "big.nrrd";
    const std::string type_name(type == VoxelType::Float32 ? "float" : type == VoxelType::Float64 ? "double" : to_string(type));
    write_attached(path, fmt::format("type: {}\ndimension: 3\nsizes: 3 2 2\nendian: big\nencoding: raw\n", type_name),
                   test::voxel_file_bytes(*expected, std::endian::big));
    test::expect_same_voxels(*expected, *read_nrrd(path));
  }
}

TEST(NrrdReader, ReadsDetachedGzipWithLineSkipAndByteSkip) {
  TempDir dir;
  const auto expected = test::make_volume(ivec3(4, 3, 2), VoxelType::UInt16);
  const std::vector<std::byte> voxels = test::voxel_file_bytes(*expected, std::endian::little);
  // gzip: line skip counts lines of the file, byte skip bytes of the
  // decompressed stream.
  const std::vector<std::byte> junk(7, std::byte{0x55});
  test::write_file(dir / "data.raw.gz",
                   test::concat({test::text_bytes("two text\nlines\n"), test::gzip(test::concat({junk, voxels}))}));
  test::write_file(dir / "vol.nhdr",
                   "NRRD0005\ntype: ushort\ndimension: 3\nsizes: 4 3 2\nspacings: 0.5 2 NaN\nencoding: gz\n"
                   "endian: little\nline skip: 2\nbyte skip: 7\ndata file: ./data.raw.gz\n");
  const auto volume = read_nrrd(dir / "vol.nhdr");
  test::expect_same_voxels(*expected, *volume);
  EXPECT_EQ(volume->spacing(), vec3(0.5f, 2.0f, 1.0f));  // NaN = unknown = 1

  // raw: byte skip -1 means "the last bytes of the file".
  test::write_file(dir / "tail.raw", test::concat({junk, junk, voxels}));
  test::write_file(dir / "tail.nhdr",
                   "NRRD0004\ntype: uint16\ndimension: 3\nsizes: 4 3 2\nencoding: raw\nbyte skip: -1\n"
                   "data file: tail.raw\n");
  test::expect_same_voxels(*expected, *read_nrrd(dir / "tail.nhdr"));
}

TEST(NrrdReader, ReadsListAndPatternDataFilesAndFourDimensionalSeries) {
  TempDir dir;
  const auto expected = test::make_volume(ivec3(3, 2, 2), VoxelType::Float32, 3);
  const std::vector<std::byte> all = test::voxel_file_bytes(*expected, std::endian::little);
  const std::size_t frame = static_cast<std::size_t>(expected->frame_bytes());
  // One gzip file per frame, named by a pattern (like shared/data/viscous_fingers).
  for (int f = 0; f < 3; ++f) {
    test::write_file(dir / fmt::format("t_{:03d}.raw.gz", 5 + 10 * f),
                     test::gzip(std::span(all).subspan(std::size_t(f) * frame, frame)));
  }
  test::write_file(dir / "series.nhdr",
                   "NRRD0004\ntype: float\ndimension: 4\nsizes: 3 2 2 3\nspacings: 1 1 1 NaN\n"
                   "kinds: domain domain domain list\nencoding: gzip\nendian: little\n"
                   "data file: t_%03d.raw.gz 5 25 10 3\n");
  const auto series = read_nrrd(dir / "series.nhdr");
  EXPECT_EQ(series->frame_count(), 3);
  test::expect_same_voxels(*expected, *series);

  // LIST with the default subdimension (dimension - 1 = 3): one file per frame,
  // raw this time, named on the lines after the field.
  for (int f = 0; f < 3; ++f) {
    test::write_file(dir / fmt::format("frame{}.raw", f), std::span(all).subspan(std::size_t(f) * frame, frame));
  }
  test::write_file(dir / "list.nhdr",
                   "NRRD0004\ntype: float\ndimension: 4\nsizes: 3 2 2 3\nencoding: raw\n"
                   "data file: LIST\nframe0.raw\nframe1.raw\nframe2.raw\n");
  test::expect_same_voxels(*expected, *read_nrrd(dir / "list.nhdr"));

  // Slices (subdim 2) of a 3D volume, one file per z.
  const auto volume = test::make_volume(ivec3(3, 2, 4), VoxelType::Int16);
  const std::vector<std::byte> bytes = test::voxel_file_bytes(*volume, std::endian::little);
  const std::size_t slice = 3 * 2 * 2;
  for (int z = 0; z < 4; ++z) {
    test::write_file(dir / fmt::format("slice{}.raw", z), std::span(bytes).subspan(std::size_t(z) * slice, slice));
  }
  test::write_file(dir / "slices.nhdr",
                   "NRRD0004\ntype: short\ndimension: 3\nsizes: 3 2 4\nencoding: raw\n"
                   "data file: slice%d.raw 0 3 1 2\n");
  test::expect_same_voxels(*volume, *read_nrrd(dir / "slices.nhdr"));
}

TEST(NrrdReader, TakesSpacingFromSpaceDirectionsAndTheOriginWhenGiven) {
  TempDir dir;
  const auto expected = test::make_volume(ivec3(2, 2, 2), VoxelType::UInt8);
  const auto path = dir / "space.nrrd";
  write_attached(path,
                 "type: uint8\ndimension: 3\nspace: left-posterior-superior\nsizes: 2 2 2\n"
                 "space directions: (0.5,0,0) (0, -2, 0) (0,0,3)\nspace origin: (10,-20.5,30)\nencoding: raw\n",
                 test::voxel_file_bytes(*expected, std::endian::little));
  const auto volume = read_nrrd(path);
  EXPECT_FLOAT_EQ(volume->spacing().x, 0.5f);
  EXPECT_FLOAT_EQ(volume->spacing().y, 2.0f);
  EXPECT_FLOAT_EQ(volume->spacing().z, 3.0f);
  EXPECT_EQ(volume->origin(), vec3(10.0f, -20.5f, 30.0f));
}

class NrrdMalformed : public ::testing::Test {
 protected:
  void expect_error(const std::string& header, std::span<const std::byte> data, std::string_view fragment) {
    const auto path = dir_ / "bad.nrrd";
    write_attached(path, header, data);
    test::expect_io_error([&] { read_nrrd(path); }, fragment);
  }
  TempDir dir_;
  std::vector<std::byte> data_ = std::vector<std::byte>(24, std::byte{1});
};

TEST_F(NrrdMalformed, SizesThatDoNotMatchTheDimension) {
  expect_error("type: uint8\ndimension: 3\nsizes: 4 6\nencoding: raw\n", data_,
               "NRRD header: 'sizes' has 2 entries but 'dimension' is 3");
}

TEST_F(NrrdMalformed, NegativeOrZeroSizes) {
  expect_error("type: uint8\ndimension: 3\nsizes: 4 -6 1\nencoding: raw\n", data_, "'sizes' entry 2 is -6");
  expect_error("type: uint8\ndimension: 3\nsizes: 4 6 0\nencoding: raw\n", data_, "'sizes' entry 3 is 0");
}

TEST_F(NrrdMalformed, UnknownTypeEncodingAndDimension) {
  expect_error("type: complex\ndimension: 3\nsizes: 4 6 1\nencoding: raw\n", data_, "type 'complex' is not supported");
  expect_error("type: int64\ndimension: 3\nsizes: 4 6 1\nencoding: raw\n", data_, "type 'int64'");
  expect_error("type: uint8\ndimension: 3\nsizes: 4 6 1\nencoding: bzip2\n", data_, "encoding 'bzip2'");
  expect_error("type: uint8\ndimension: 2\nsizes: 4 6\nencoding: raw\n", data_, "'dimension' is 2");
  expect_error("type: uint8\ndimension: 4\nsizes: 3 4 6 1\nkinds: RGB-color domain domain domain\nencoding: raw\n",
               data_, "scalar voxels only");
  expect_error("type: uint8\nsizes: 4 6 1\nencoding: raw\n", data_, "'dimension' is missing");
}

TEST_F(NrrdMalformed, TruncatedRawPayload) {
  expect_error("type: uint8\ndimension: 3\nsizes: 5 5 5\nencoding: raw\n", data_, "truncated");
}

TEST_F(NrrdMalformed, BadGzipPayload) {
  std::vector<std::byte> packed = test::gzip(std::vector<std::byte>(4096, std::byte{9}));
  packed.resize(packed.size() / 2);
  expect_error("type: uint8\ndimension: 3\nsizes: 16 16 16\nencoding: gzip\n", packed, "truncated");
  expect_error("type: uint8\ndimension: 3\nsizes: 2 3 4\nencoding: gzip\n", data_, "corrupt compressed data");
}

TEST_F(NrrdMalformed, HeaderClaimingHundredGigabytes) {
  const auto path = dir_ / "huge.nrrd";
  write_attached(path, "type: uint8\ndimension: 3\nsizes: 5000 5000 4000\nencoding: gzip\n", test::gzip(data_));
  const std::uint64_t previous = memory_budget_bytes();
  set_memory_budget_bytes(std::uint64_t(1) << 30);
  EXPECT_THROW(read_nrrd(path), OutOfMemoryBudget);
  set_memory_budget_bytes(std::uint64_t(200) << 30);  // allowed, but 24 gzip bytes cannot hold it
  EXPECT_THROW(read_nrrd(path), IoError);
  set_memory_budget_bytes(previous);
}

TEST_F(NrrdMalformed, MissingDataFileAndBadPatterns) {
  test::write_file(dir_ / "missing.nhdr",
                   "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 2 3 4\nencoding: raw\ndata file: nothere.raw\n");
  test::expect_io_error([&] { read_nrrd(dir_ / "missing.nhdr"); }, "file not found");
  test::write_file(dir_ / "pattern.nhdr",
                   "NRRD0004\ntype: uint8\ndimension: 4\nsizes: 2 3 4 5\nencoding: raw\ndata file: f%03d.raw 1 3 1\n");
  test::expect_io_error([&] { read_nrrd(dir_ / "pattern.nhdr"); }, "needs 5");
  test::write_file(dir_ / "evil.nhdr",
                   "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 2 3 4\nencoding: raw\ndata file: %s%n 1 4 1\n");
  test::expect_io_error([&] { read_nrrd(dir_ / "evil.nhdr"); }, "integer conversion");
}

TEST_F(NrrdMalformed, NotANrrdOrEmptyOrBinaryGarbage) {
  test::write_file(dir_ / "empty.nrrd", "");
  test::expect_io_error([&] { read_nrrd(dir_ / "empty.nrrd"); }, "not a NRRD file");
  test::write_file(dir_ / "text.nrrd", "hello\nworld\n");
  test::expect_io_error([&] { read_nrrd(dir_ / "text.nrrd"); }, "not a NRRD file");
  expect_error("type: uint8\ndimension: 3\nsizes: 2 3 4\nencoding: raw\nthis line has no colon\n", data_,
               "neither 'field: value'");
  expect_error("type: uint8\ndimension: 3\nsizes: 2 3 4\nencoding: raw\nbyte skip: -1\nencoding: gzip\n", data_,
               "appears twice");
  expect_error("type: uint8\ndimension: 3\nsizes: 2 3 4\nspacings: 1 0 1\nencoding: raw\n", data_, "spacing 0");
  expect_error("type: uint8\ndimension: 3\nsizes: 2 3 4\nspace directions: (1,0,0) (0,1,0\nencoding: raw\n", data_,
               "without ')'");
}

// NaN is NRRD's "unknown" spacing (unit spacing); a negative one is a
// flipped axis (its magnitude); one beyond a float was undefined behaviour.
TEST(NrrdReader, SpacingsUnknownNegativeAndOutOfRange) {
  TempDir dir;
  const auto path = dir / "s.nrrd";
  const std::vector<std::byte> data(24, std::byte{1});
  write_attached(path, "type: uint8\ndimension: 3\nsizes: 4 3 2\nspacings: nan -2 0.5\nencoding: raw\n", data);
  EXPECT_EQ(read_nrrd(path)->spacing(), vec3(1.0f, 2.0f, 0.5f));
  write_attached(path, "type: uint8\ndimension: 3\nsizes: 4 3 2\nspacings: 1 1e300 1\nencoding: raw\n", data);
  test::expect_io_error([&] { read_nrrd(path); }, "axis 2 has spacing 1e+300");
  write_attached(path, "type: uint8\ndimension: 3\nsizes: 4 3 2\nspacings: 1 1 1e-300\nencoding: raw\n", data);
  test::expect_io_error([&] { read_nrrd(path); }, "axis 3 has spacing 1e-300");
}

}  // namespace
}  // namespace penumbra

#include "penumbra/io/vti_reader.h"

#include "penumbra/io/base64.h"
#include "penumbra/io/io_test_support.h"

#include <fmt/format.h>

#include <cmath>
#include <gtest/gtest.h>

#include <cstring>

namespace penumbra {
namespace {

using test::TempDir;

TEST(VtiReader, ReadsAsciiArrayNamedByScalarsWithAttributesInAnyOrder) {
  TempDir dir;
  const auto path = dir / "hand.vti";
  test::write_file(path,
                   "<?xml version=\"1.0\"?>\n<!-- written by hand -->\n"
                   "<VTKFile version='0.1' type='ImageData' byte_order='LittleEndian'>\n"
                   "  <ImageData Spacing=\"0.5 1 2\"\n   Origin=\"10 20 30\" WholeExtent=\"1 3 0 1 2 2\">\n"
                   "  <Piece Extent=\"1 3 0 1 2 2\">\n"
                   "    <PointData Scalars=\"density\">\n"
                   "      <DataArray Name=\"other\" type=\"Float32\" format=\"ascii\">9 9 9 9 9 9</DataArray>\n"
                   "      <DataArray format=\"ascii\" type=\"Int16\" Name=\"density\">\n"
                   "        -3 0 7\n 12   -32768 32767\n      </DataArray>\n"
                   "    </PointData>\n  </Piece>\n  </ImageData>\n</VTKFile>\n");
  const auto volume = read_vti(path);
  EXPECT_EQ(volume->dims(), ivec3(3, 2, 1));
  EXPECT_EQ(volume->type(), VoxelType::Int16);
  EXPECT_EQ(volume->spacing(), vec3(0.5f, 1.0f, 2.0f));
  // The origin of index (0,0,0) includes the extent's start.
  EXPECT_EQ(volume->origin(), vec3(10.5f, 20.0f, 34.0f));
  EXPECT_FLOAT_EQ(volume->voxel(0, ivec3(0, 0, 0)), -3.0f);
  EXPECT_FLOAT_EQ(volume->voxel(0, ivec3(2, 0, 0)), 7.0f);
  EXPECT_FLOAT_EQ(volume->voxel(0, ivec3(1, 1, 0)), -32768.0f);
  EXPECT_EQ(volume->source(), path.string());
}

// The base64 body VTK writes for a binary array: one header word with the
// byte count, then the data (a UInt32 header here, as in version 0.1 files).
std::string binary_body(std::span<const std::byte> data) {
  const std::uint32_t size = static_cast<std::uint32_t>(data.size());
  std::vector<std::byte> joined(4);
  std::memcpy(joined.data(), &size, 4);
  joined.insert(joined.end(), data.begin(), data.end());
  return base64_encode(joined);
}

std::string vti_with_binary_array(std::string_view body, std::string_view extra_root = {},
                                  std::string_view array_attributes = "type=\"UInt8\"") {
  return std::string("<VTKFile type=\"ImageData\" version=\"0.1\" byte_order=\"LittleEndian\" ") +
         std::string(extra_root) + ">\n<ImageData WholeExtent=\"0 1 0 1 0 1\" Origin=\"0 0 0\" Spacing=\"1 1 1\">\n" +
         "<Piece Extent=\"0 1 0 1 0 1\"><PointData>\n<DataArray " + std::string(array_attributes) +
         " Name=\"s\" format=\"binary\">\n" + std::string(body) +
         "\n</DataArray></PointData></Piece></ImageData></VTKFile>\n";
}

TEST(VtiReader, ReadsInlineBinaryWithUInt32Header) {
  TempDir dir;
  const auto expected = test::make_volume(ivec3(2), VoxelType::UInt8);
  test::write_file(dir / "b.vti", vti_with_binary_array(binary_body(test::voxel_file_bytes(*expected, std::endian::little))));
  test::expect_same_voxels(*expected, *read_vti(dir / "b.vti"));
}

TEST(VtiReader, MalformedFilesGiveIoError) {
  TempDir dir;
  const auto path = dir / "bad.vti";
  const auto expect = [&](const std::string& text, std::string_view fragment) {
    test::write_file(path, text);
    test::expect_io_error([&] { read_vti(path); }, fragment);
  };
  const std::vector<std::byte> eight(8, std::byte{4});
  expect(vti_with_binary_array("AAAA*AAAAAAA"), "bad base64");
  expect(vti_with_binary_array(binary_body(std::span(eight).first(7))), "holds 7 bytes");
  expect(vti_with_binary_array(binary_body(eight).substr(0, 8)), "ended early");
  expect(vti_with_binary_array(binary_body(eight).substr(0, 4)), "DataArray needs 8 bytes");
  expect(vti_with_binary_array(binary_body(eight), "compressor=\"vtkLZ4DataCompressor\""), "vtkLZ4DataCompressor");
  expect(vti_with_binary_array(binary_body(eight), "", "type=\"Int64\""), "type 'Int64' is not supported");
  expect(vti_with_binary_array(binary_body(eight), "", "type=\"UInt8\" NumberOfComponents=\"3\""), "3 components");
  // A compression header whose block sizes do not add up to the extent.
  std::vector<std::byte> header(16);
  const std::uint32_t words[4] = {1, 32768, 5, 10};
  std::memcpy(header.data(), words, 16);
  expect(vti_with_binary_array(base64_encode(header), "compressor=\"vtkZLibDataCompressor\""), "holds 5 bytes");
  expect("<VTKFile type=\"PolyData\"></VTKFile>", "penumbra reads ImageData");
  expect("<Other/>", "not <VTKFile>");
  expect("not xml at all", "no <VTKFile>");
  expect("<VTKFile type=\"ImageData\"><ImageData WholeExtent=\"0 -1 0 1 0 1\"><PointData>"
         "<DataArray type=\"UInt8\" format=\"ascii\">1</DataArray></PointData></ImageData></VTKFile>",
         "WholeExtent axis 1");
  expect("<VTKFile type=\"ImageData\"><ImageData WholeExtent=\"0 1 0 0 0 0\"><PointData>"
         "<DataArray type=\"UInt8\" format=\"ascii\">1 2 3</DataArray></PointData></ImageData></VTKFile>",
         "more than the 2 values");
  expect("<VTKFile type=\"ImageData\"><ImageData WholeExtent=\"0 1 0 0 0 0\"><PointData>"
         "<DataArray type=\"UInt8\" format=\"ascii\">1 300</DataArray></PointData></ImageData></VTKFile>",
         "'300' is not a valid uint8");
  expect("<VTKFile type=\"ImageData\"><ImageData WholeExtent=\"0 1 0 0 0 0\"><PointData>"
         "<DataArray type=\"UInt8\" format=\"appended\" offset=\"0\"/></PointData></ImageData>"
         "<AppendedData encoding=\"raw\">_\x08\x00\x00\x00</AppendedData></VTKFile>",
         "needs 2 bytes");
  expect("<VTKFile type=\"ImageData\"><ImageData WholeExtent=\"0 1 0 0 0 0\"><PointData>"
         "<DataArray type=\"UInt8\" format=\"appended\" offset=\"0\"/></PointData></ImageData></VTKFile>",
         "no <AppendedData>");
}

std::string ascii_vti(std::string_view type, std::string_view values, std::string_view extent = "0 1 0 0 0 0") {
  return fmt::format("<VTKFile type='ImageData'><ImageData WholeExtent='{}'><Piece><PointData>"
                     "<DataArray type='{}' format='ascii'>{}</DataArray></PointData></Piece></ImageData></VTKFile>",
                     extent, type, values);
}

// Each of these was undefined behaviour (a double cast to int64) before.
TEST(VtiReader, AsciiValuesOutsideTheTypeAreErrorsNotUndefinedBehaviour) {
  TempDir dir;
  const auto path = dir / "v.vti";
  for (const char* bad : {"1e30", "-1e30", "inf", "nan", "1234567890123456789012345678901234567890", "32768",
                          "12.5"}) {
    test::write_file(path, ascii_vti("Int16", fmt::format("1 {}", bad)));
    test::expect_io_error([&] { read_vti(path); }, fmt::format("ascii value 1 '{}' is not a valid int16", bad));
  }
  test::write_file(path, ascii_vti("Int16", "12.0 -32768"));
  EXPECT_FLOAT_EQ(read_vti(path)->voxel(0, ivec3(0, 0, 0)), 12.0f);
  test::write_file(path, ascii_vti("Float32", "1 1e300"));
  test::expect_io_error([&] { read_vti(path); }, "ascii value 1 '1e300' is not a valid float32");
  test::write_file(path, ascii_vti("Float32", "nan inf"));  // representable: kept
  EXPECT_TRUE(std::isnan(read_vti(path)->voxel(0, ivec3(0, 0, 0))));
}

TEST(VtiReader, AnExtentTooLongForAnAxisSaysSo) {
  TempDir dir;
  const auto path = dir / "v.vti";
  test::write_file(path, ascii_vti("UInt8", "1 2", "0 2147483647 0 0 0 0"));
  test::expect_io_error([&] { read_vti(path); }, "2147483648 points, more than the 2147483647 an axis can have");
  test::write_file(path, ascii_vti("UInt8", "1 2", "0 1.5 0 0 0 0"));
  test::expect_io_error([&] { read_vti(path); }, "extents are integers");
}

}  // namespace
}  // namespace penumbra

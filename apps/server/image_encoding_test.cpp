#include "server/image_encoding.h"

#include "penumbra/base/error.h"
#include "penumbra/io/image_io.h"
#include "server_test_support.h"

#include <gtest/gtest.h>

#include <cstdlib>

namespace penumbra::server {
namespace {

// A ramp through the dark end (where the sRGB curve is steepest) and a colour
// per row, so every code path of the table is exercised.
Image ramp_image() {
  Image image(256, 8);
  for (int y = 0; y < 8; ++y) {
    for (int x = 0; x < 256; ++x) {
      const float t = float(x) / 255.0f;
      image.at(x, y) = vec4(t * t * t, t, float(y) / 7.0f, 1.0f);
    }
  }
  return image;
}

TEST(ImageEncoding, SrgbCodesMatchThePngWriter) {
  const Image image = ramp_image();
  const std::vector<std::uint8_t> ours = to_srgb8(image);
  // decode_png(encode_png) gives back linear values; the PNG's own 8-bit
  // codes are recovered by encoding them again exactly (round trip of codes).
  const Image png = decode_png(encode_png(image));
  const std::vector<std::uint8_t> png_codes = to_srgb8(png);
  int max_difference = 0;
  for (std::size_t i = 0; i < ours.size(); ++i) max_difference = std::max(max_difference, std::abs(ours[i] - png_codes[i]));
  // The table rounds its input to 1/16384; next to a rounding tie that moves a
  // code by one (image_encoding.cpp), never more.
  EXPECT_LE(max_difference, 1);
}

TEST(ImageEncoding, ClampsAndZeroesNonFiniteValues) {
  Image image(3, 1);
  image.at(0, 0) = vec4(-1.0f, 2.0f, std::nanf(""), 1.0f);
  image.at(1, 0) = vec4(0.5f, 1.0f, 0.0f, 1.0f);
  const std::vector<std::uint8_t> rgb = to_srgb8(image);
  EXPECT_EQ(rgb[0], 0);
  EXPECT_EQ(rgb[1], 255);
  EXPECT_EQ(rgb[2], 0);
  EXPECT_EQ(rgb[3], 188);  // sRGB(0.5) = 0.7354 -> 187.5 -> 188
}

TEST(ImageEncoding, JpegDecodesToTheSameImageWithinCompressionError) {
  const Image image = ramp_image();
  const std::vector<std::uint8_t> jpeg = encode_jpeg(image, 95);
  ASSERT_GT(jpeg.size(), 4u);
  EXPECT_EQ(jpeg[0], 0xFF);
  EXPECT_EQ(jpeg[1], 0xD8);
  int w = 0, h = 0;
  const auto decoded = testing::decode_jpeg(std::string(jpeg.begin(), jpeg.end()), w, h);
  EXPECT_EQ(w, 256);
  EXPECT_EQ(h, 8);
  const std::vector<std::uint8_t> exact = to_srgb8(image);
  double sum = 0.0;
  for (std::size_t i = 0; i < exact.size(); ++i) sum += std::abs(int(decoded[i]) - int(exact[i]));
  // Quality 95 with full-resolution chroma on smooth ramps: a mean error of
  // a code or two; 3 leaves room for libjpeg versions.
  EXPECT_LT(sum / double(exact.size()), 3.0);
}

TEST(ImageEncoding, LowerQualityGivesSmallerFiles) {
  const Image image = ramp_image();
  EXPECT_LT(encode_jpeg(image, 30).size(), encode_jpeg(image, 95).size());
}

TEST(ImageEncoding, RejectsBadQualityAndEmptyImages) {
  EXPECT_THROW(encode_jpeg(ramp_image(), 0), InvalidArgument);
  EXPECT_THROW(encode_jpeg(ramp_image(), 101), InvalidArgument);
  EXPECT_THROW(encode_jpeg(Image(), 80), InvalidArgument);
}

TEST(ImageEncoding, FormatNames) {
  EXPECT_EQ(image_format_from_string("jpeg"), ImageFormat::Jpeg);
  EXPECT_EQ(image_format_from_string("jpg"), ImageFormat::Jpeg);
  EXPECT_EQ(image_format_from_string("png"), ImageFormat::Png);
  EXPECT_FALSE(image_format_from_string("gif"));
  EXPECT_EQ(mime_type(ImageFormat::Png), "image/png");
}

}  // namespace
}  // namespace penumbra::server

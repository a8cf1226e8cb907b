#include "penumbra/io/image_io.h"

#include "penumbra/io/io_test_support.h"

#include <gtest/gtest.h>

#include <cmath>

namespace penumbra {
namespace {

using test::TempDir;

Image gradient_image(int width, int height) {
  Image image(width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      image.at(x, y) = vec4(float(x) / float(width - 1), float(y) / float(height - 1),
                            std::pow(float(x + y) / float(width + height - 2), 3.0f), 0.5f);
    }
  }
  return image;
}

TEST(ImageIo, ExrRoundTripIsExactForFloats) {
  TempDir dir;
  Image image = gradient_image(17, 9);
  image.at(0, 0) = vec4(-2.5f, 1e6f, 3.0e-8f, 0.25f);  // HDR, negative and tiny values survive
  write_exr(dir / "a.exr", image);
  const Image back = read_exr(dir / "a.exr");
  ASSERT_EQ(back.width(), 17);
  ASSERT_EQ(back.height(), 9);
  for (std::size_t i = 0; i < image.pixel_count(); ++i) EXPECT_EQ(back.data()[i], image.data()[i]) << i;
}

TEST(ImageIo, PngRoundTripIsWithinOneCodeOfSrgb) {
  TempDir dir;
  const Image image = gradient_image(33, 20);
  write_png(dir / "a.png", image);
  const Image back = read_png(dir / "a.png");
  ASSERT_EQ(back.width(), 33);
  ASSERT_EQ(back.height(), 20);
  const auto encode = [](float linear) {
    return linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
  };
  for (std::size_t i = 0; i < image.pixel_count(); ++i) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(encode(back.data()[i][c]), encode(image.data()[i][c]), 0.5f / 255.0f + 1e-5f);
    }
    EXPECT_EQ(back.data()[i].a, 1.0f);  // PNG is written as RGB
  }
  // The encoder and the file writer produce the same bytes.
  const std::vector<std::uint8_t> bytes = encode_png(image);
  EXPECT_EQ(bytes.size(), std::filesystem::file_size(dir / "a.png"));
  const Image decoded = decode_png(bytes);
  EXPECT_EQ(decoded.pixels(), back.pixels());
}

TEST(ImageIo, PngUsesTheExactSrgbCurveAndClamps) {
  Image image(4, 1);
  image.at(0, 0) = vec4(0.2158605f, 0.0f, 1.0f, 1.0f);  // the linear value of code 128
  image.at(1, 0) = vec4(-1.0f, 7.0f, std::nanf(""), 1.0f);
  image.at(2, 0) = vec4(0.0031308f, 0.001f, 0.5f, 1.0f);
  const Image back = decode_png(encode_png(image));
  EXPECT_NEAR(back.at(0, 0).r, 0.2158605f, 1e-6f);  // code 128 decoded
  EXPECT_EQ(back.at(0, 0).g, 0.0f);
  EXPECT_EQ(back.at(0, 0).b, 1.0f);
  EXPECT_EQ(back.at(1, 0).r, 0.0f);
  EXPECT_EQ(back.at(1, 0).g, 1.0f);
  EXPECT_EQ(back.at(1, 0).b, 0.0f);
  EXPECT_NEAR(back.at(2, 0).g, 0.00091058f, 1e-7f);  // linear segment: 0.001 * 12.92 * 255 = 3.29 -> code 3
  EXPECT_NEAR(back.at(2, 0).b, 0.5028865f, 1e-6f);  // 0.5 encodes to 187.516 -> code 188
}

TEST(ImageIo, ErrorsAreIoErrors) {
  TempDir dir;
  test::expect_io_error([&] { read_png(dir / "absent.png"); }, "file not found");
  test::expect_io_error([&] { read_exr(dir / "absent.exr"); }, "file not found");
  test::write_file(dir / "junk.png", "\x89PNG but not really");
  test::expect_io_error([&] { read_png(dir / "junk.png"); }, "junk.png");
  test::write_file(dir / "junk.exr", "v/1\x01 not an exr");
  test::expect_io_error([&] { read_exr(dir / "junk.exr"); }, "cannot read EXR");
  test::expect_io_error([&] { write_png(dir / "empty.png", Image()); }, "empty");
  test::expect_io_error([&] { write_exr(dir / "empty.exr", Image()); }, "empty");
  test::expect_io_error([&] { write_png("/nonexistent-dir-penumbra/a.png", Image(2, 2)); }, "cannot open");
  test::expect_io_error([&] { write_exr("/nonexistent-dir-penumbra/a.exr", Image(2, 2)); }, "cannot write EXR");
}

}  // namespace
}  // namespace penumbra

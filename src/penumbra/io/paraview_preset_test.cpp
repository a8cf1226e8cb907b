#include "penumbra/io/paraview_preset.h"

#include "penumbra/io/io_test_support.h"

#include <gtest/gtest.h>

namespace penumbra {
namespace {

using test::TempDir;

constexpr const char* kPresets = R"([
  {"Name": "Indexed", "IndexedColors": [1, 0, 0, 0, 1, 0]},
  {"Name": "Grey ramp", "ColorSpace": "RGB", "RGBPoints": [-10, 0, 0, 0,  30, 1, 1, 1]},
  {"Name": "With opacity", "ColorSpace": "Diverging", "NanColor": [1, 1, 0],
   "RGBPoints": [0, 0.5, 0.5, 0.5,  100, 1, 0, 0,  200, 0, 0, 1],
   "Points": [0, 0, 0.5, 0,  50, 0.8, 0.25, 0,  200, 0.2, 0.5, 0]}
])";

TEST(ParaviewPreset, ConvertsSrgbStopsToLinearAndNormalisesTheRange) {
  TempDir dir;
  test::write_file(dir / "presets.json", kPresets);
  const TransferFunction tf = read_paraview_preset(dir / "presets.json", "With opacity");
  EXPECT_FALSE(tf.range().has_value());  // "data"
  // Stops: colour at 0, 0.5, 1; opacity at 0, 0.25, 1 and, because the
  // stop at 50 has midpoint 0.25, at 50 + 0.25 * 150 = 87.5 -> 0.4375.
  const auto& p = tf.points();
  ASSERT_EQ(p.size(), 5u);
  EXPECT_FLOAT_EQ(p[0].value, 0.0f);
  EXPECT_FLOAT_EQ(p[1].value, 0.25f);
  EXPECT_FLOAT_EQ(p[2].value, 0.4375f);
  EXPECT_FLOAT_EQ(p[3].value, 0.5f);
  EXPECT_FLOAT_EQ(p[4].value, 1.0f);
  // sRGB 0.5 is linear 0.21404.
  EXPECT_NEAR(p[0].color.r, 0.21404f, 1e-5f);
  EXPECT_NEAR(p[0].color.g, 0.21404f, 1e-5f);
  // At 0.25 the sRGB colour is halfway between grey 0.5 and red: (0.75, 0.25, 0.25).
  EXPECT_NEAR(p[1].color.r, 0.52252f, 1e-4f);
  EXPECT_NEAR(p[1].color.g, 0.05087f, 1e-4f);
  EXPECT_EQ(p[3].color, vec3(1.0f, 0.0f, 0.0f));
  EXPECT_EQ(p[4].color, vec3(0.0f, 0.0f, 1.0f));
  EXPECT_FLOAT_EQ(p[0].alpha, 0.0f);
  EXPECT_FLOAT_EQ(p[1].alpha, 0.8f);
  EXPECT_FLOAT_EQ(p[2].alpha, 0.5f);    // the midpoint holds the average of 0.8 and 0.2
  EXPECT_NEAR(p[3].alpha, 0.5f - 0.3f / 9.0f, 1e-6f);  // 1/9 of the way from 0.4375 (0.5) to 1 (0.2)
  EXPECT_FLOAT_EQ(p[4].alpha, 0.2f);
}

TEST(ParaviewPreset, WithoutOpacityPointsUsesALinearRampAndFirstPresetWithColours) {
  const TransferFunction tf = parse_paraview_preset(kPresets);  // "Indexed" has no RGBPoints: skipped
  ASSERT_EQ(tf.points().size(), 2u);
  EXPECT_EQ(tf.points()[0].value, 0.0f);
  EXPECT_EQ(tf.points()[0].alpha, 0.0f);
  EXPECT_EQ(tf.points()[1].value, 1.0f);
  EXPECT_EQ(tf.points()[1].alpha, 1.0f);
  EXPECT_EQ(tf.points()[1].color, vec3(1.0f));
  // A single object is a file with one preset.
  const TransferFunction single =
      parse_paraview_preset(R"({"Name": "one", "RGBPoints": [5, 0.5, 0.5, 0.5]})", "one");
  EXPECT_NEAR(single.evaluate(0.7f).g, 0.21404f, 1e-5f);
}

TEST(ParaviewPreset, UnknownNamesAndMalformedPresetsGiveIoError) {
  test::expect_io_error([] { parse_paraview_preset(kPresets, "Viridis"); },
                        "no preset named 'Viridis'; the file has 'Indexed', 'Grey ramp', 'With opacity'");
  test::expect_io_error([] { parse_paraview_preset(kPresets, "Indexed"); }, "indexed colour maps are not supported");
  test::expect_io_error([] { parse_paraview_preset("[{\"Name\": \"x\", \"RGBPoints\": [0, 1, 1]}]"); },
                        "groups of 4");
  test::expect_io_error([] { parse_paraview_preset("[{\"Name\": \"x\", \"RGBPoints\": [0, 1, 1, \"red\"]}]"); },
                        "non-number");
  test::expect_io_error([] { parse_paraview_preset("[{\"Name\": \"x\", \"RGBPoints\": [0, 1,"); }, "invalid JSON");
  test::expect_io_error([] { parse_paraview_preset("42"); }, "expected an array");
  test::expect_io_error([] { read_paraview_preset("/nonexistent-dir-penumbra/p.json"); }, "file not found");
}

TEST(ParaviewPreset, ReadsTheXmlColorMapForm) {
  TempDir dir;
  test::write_file(dir / "maps.xml",
                   "<ColorMaps>\n<ColorMap name=\"Warm\" space=\"RGB\">\n"
                   "  <Point x=\"2\" o=\"0\" r=\"0\" g=\"0\" b=\"0\"/>\n"
                   "  <Point x=\"4\" o=\"1\" r=\"1\" g=\"0.5\" b=\"0\"/>\n"
                   "  <NaN r=\"1\" g=\"1\" b=\"0\"/>\n</ColorMap>\n"
                   "<ColorMap name=\"Other\"><Point x=\"0\" r=\"1\" g=\"1\" b=\"1\"/></ColorMap>\n</ColorMaps>\n");
  EXPECT_EQ(paraview_preset_names(dir / "maps.xml"), (std::vector<std::string>{"Warm", "Other"}));
  const TransferFunction tf = read_paraview_preset(dir / "maps.xml", "Warm");
  ASSERT_EQ(tf.points().size(), 2u);
  EXPECT_NEAR(tf.points()[1].color.g, 0.21404f, 1e-5f);
  EXPECT_EQ(tf.points()[1].alpha, 1.0f);
}

TEST(ParaviewPreset, NumbersBeyondADoubleAreIoErrors) {
  EXPECT_THROW(parse_paraview_preset(R"([{"Name": "x", "RGBPoints": [0, 0, 0, 0, 1e400, 1, 1, 1]}])"), IoError);
}

}  // namespace
}  // namespace penumbra

// Tests of the io building blocks: base64, inflate limits, the XML scanner,
// file-name patterns and strict number parsing.
#include "penumbra/io/base64.h"
#include "penumbra/io/compression.h"
#include "penumbra/io/file_pattern.h"
#include "penumbra/io/io_test_support.h"
#include "penumbra/io/text_parsing.h"
#include "penumbra/io/xml_scanner.h"

#include <gtest/gtest.h>

#include <numeric>

namespace penumbra {
namespace {

std::vector<std::byte> iota_bytes(std::size_t n, int start = 0) {
  std::vector<std::byte> bytes(n);
  for (std::size_t i = 0; i < n; ++i) bytes[i] = std::byte((start + int(i) * 37) & 255);
  return bytes;
}

TEST(IoBase64, RoundTripsEveryLengthRemainder) {
  for (std::size_t n = 0; n < 12; ++n) {
    const std::vector<std::byte> data = iota_bytes(n, int(n));
    const std::string text = base64_encode(data);
    EXPECT_EQ(text.size() % 4, 0u);
    Base64Decoder decoder(text);
    std::vector<std::byte> decoded(n);
    ASSERT_TRUE(decoder.read_exact(decoded)) << decoder.error();
    EXPECT_EQ(decoded, data) << "length " << n;
  }
  EXPECT_EQ(base64_encode(test::text_bytes("Man")), "TWFu");
  EXPECT_EQ(base64_encode(test::text_bytes("Ma")), "TWE=");
}

TEST(IoBase64, DecodesSeparatelyPaddedStreamsBackToBackAndSkipsWhitespace) {
  // VTK encodes a compression header and the blocks as two streams.
  const std::string text = base64_encode(test::text_bytes("ab")) + "\n  " + base64_encode(test::text_bytes("cde"));
  Base64Decoder decoder(text);
  std::string out(5, '?');
  ASSERT_TRUE(decoder.read_exact(std::as_writable_bytes(std::span(out.data(), out.size()))));
  EXPECT_EQ(out, "abcde");
}

TEST(IoBase64, RejectsInvalidCharactersAndShortInput) {
  std::vector<std::byte> out(3);
  Base64Decoder bad("TW*u");
  EXPECT_FALSE(bad.read_exact(out));
  EXPECT_NE(bad.error().find("invalid base64 character"), std::string::npos);
  Base64Decoder short_input("TWFu");
  std::vector<std::byte> more(6);
  EXPECT_FALSE(short_input.read_exact(more));
  Base64Decoder misplaced("T===");
  EXPECT_FALSE(misplaced.read_exact(out));
}

TEST(IoCompression, InflatesGzipAndZlibAndConcatenatedGzipMembers) {
  const std::vector<std::byte> a = iota_bytes(100000, 1);
  const std::vector<std::byte> b = iota_bytes(5000, 7);
  for (CompressionFormat format : {CompressionFormat::Gzip, CompressionFormat::Zlib}) {
    const std::vector<std::byte> packed = deflate_bytes(a, format);
    std::vector<std::byte> out(a.size());
    InflateStream(packed, "memory").read_exact(out, "data");
    EXPECT_EQ(out, a);
  }
  const std::vector<std::byte> members =
      test::concat({deflate_bytes(a, CompressionFormat::Gzip), deflate_bytes(b, CompressionFormat::Gzip)});
  std::vector<std::byte> out(a.size() + b.size());
  InflateStream(members, "memory").read_exact(out, "data");
  EXPECT_EQ(out, test::concat({a, b}));
}

TEST(IoCompression, ProducesOnlyWhatIsAskedForSoZipBombsCostNothing) {
  // 64 MiB of zeros compress to about 64 KiB; reading 16 bytes of it must
  // inflate (and allocate) no more than that.
  const std::size_t huge = std::size_t(64) << 20;
  std::vector<std::byte> zeros(1 << 20);
  std::vector<std::byte> packed;
  Deflater deflater(CompressionFormat::Gzip, 9);
  const ByteSink append = [&](std::span<const std::byte> p) { packed.insert(packed.end(), p.begin(), p.end()); };
  for (std::size_t i = 0; i < huge / zeros.size(); ++i) deflater.write(zeros, append);
  deflater.finish(append);
  EXPECT_LT(packed.size(), huge / 500);
  InflateStream stream(packed, "bomb");
  std::vector<std::byte> out(16);
  stream.read_exact(out, "data");
  EXPECT_EQ(stream.position(), 16u);
  EXPECT_GT(max_inflated_size(packed.size()), huge);  // the plausibility bound still admits it
  EXPECT_LT(max_inflated_size(1000), 2'000'000u);
}

TEST(IoCompression, TruncatedAndCorruptStreamsThrowIoError) {
  const std::vector<std::byte> data = iota_bytes(50000, 3);
  std::vector<std::byte> packed = deflate_bytes(data, CompressionFormat::Gzip);
  std::vector<std::byte> out(data.size());
  const std::vector<std::byte> truncated(packed.begin(), packed.begin() + std::ptrdiff_t(packed.size() / 2));
  test::expect_io_error([&] { InflateStream(truncated, "t.gz").read_exact(out, "voxel data"); }, "truncated");
  std::vector<std::byte> corrupt = packed;
  for (std::size_t i = 20; i < 60; ++i) corrupt[i] = std::byte(0xff);
  test::expect_io_error([&] { InflateStream(corrupt, "c.gz").read_exact(out, "voxel data"); }, "c.gz");
  const std::string not_gzip = "this is plain text, not a compressed stream";
  test::expect_io_error([&] { InflateStream(test::text_bytes(not_gzip), "p.gz").read_exact(out, "voxel data"); },
                        "corrupt compressed data");
}

TEST(XmlScanner, ReadsTagsAndAttributesInAnyOrderSkippingCommentsAndDeclarations) {
  const std::string xml =
      "<?xml version=\"1.0\"?>\n<!-- <Fake a=\"1\"/> -->\n<!DOCTYPE x>\n"
      "<Root   b = 'two'\n a=\"1 &amp; &lt;3&gt; &#65;&#x42;\" >text<![CDATA[<NotATag/>]]>"
      "<Child/></Root>";
  XmlScanner scanner(xml, "test.xml");
  auto root = scanner.next();
  ASSERT_TRUE(root);
  EXPECT_EQ(root->name, "Root");
  EXPECT_EQ(root->kind, XmlTag::Kind::Start);
  ASSERT_NE(root->attribute("a"), nullptr);
  EXPECT_EQ(*root->attribute("a"), "1 & <3> AB");
  EXPECT_EQ(*root->attribute("b"), "two");
  EXPECT_EQ(root->attribute("c"), nullptr);
  EXPECT_EQ(xml.substr(root->end, 4), "text");
  auto child = scanner.next();
  ASSERT_TRUE(child);
  EXPECT_EQ(child->name, "Child");
  EXPECT_EQ(child->kind, XmlTag::Kind::SelfClosing);
  auto end = scanner.next();
  ASSERT_TRUE(end);
  EXPECT_EQ(end->kind, XmlTag::Kind::End);
  EXPECT_FALSE(scanner.next());
}

TEST(XmlScanner, MalformedMarkupThrowsIoError) {
  for (std::string_view bad : {"<A b=1>", "<A b=\"1>", "<A", "<!-- open", "<A b>"}) {
    XmlScanner scanner(bad, "bad.xml");
    test::expect_io_error([&] { while (scanner.next()) {} }, "bad.xml");
  }
}

TEST(IoFilePattern, ExpandsPrintfStyleNamesWithoutPrintf) {
  std::string error;
  const auto names = expand_file_pattern("vf_t%03d_64.raw.gz", 1, 91, 10, 100, error);
  ASSERT_TRUE(names) << error;
  ASSERT_EQ(names->size(), 10u);
  EXPECT_EQ(names->front(), "vf_t001_64.raw.gz");
  EXPECT_EQ(names->back(), "vf_t091_64.raw.gz");
  const auto down = expand_file_pattern("s%d%%.raw", 3, 1, -1, 100, error);
  ASSERT_TRUE(down) << error;
  EXPECT_EQ(*down, (std::vector<std::string>{"s3%.raw", "s2%.raw", "s1%.raw"}));
  EXPECT_EQ(expand_file_pattern("%4d|", 7, 7, 1, 1, error)->front(), "   7|");
  EXPECT_EQ(expand_file_pattern("%-3d|", 7, 7, 1, 1, error)->front(), "7  |");
  EXPECT_EQ(expand_file_pattern("%+04d", 7, 7, 1, 1, error)->front(), "+007");
  EXPECT_EQ(expand_file_pattern("%03d", -7, -7, 1, 1, error)->front(), "-07");
}

TEST(IoFilePattern, RejectsOtherConversionsZeroStepsAndEmptyRanges) {
  std::string error;
  EXPECT_FALSE(expand_file_pattern("%s.raw", 1, 2, 1, 10, error));
  EXPECT_FALSE(expand_file_pattern("%d_%d.raw", 1, 2, 1, 10, error));
  EXPECT_FALSE(expand_file_pattern("plain.raw", 1, 2, 1, 10, error));
  EXPECT_FALSE(expand_file_pattern("%d.raw", 1, 5, 0, 10, error));
  EXPECT_FALSE(expand_file_pattern("%d.raw", 5, 1, 1, 10, error));
  EXPECT_FALSE(expand_file_pattern("%d.raw", 0, 1000000000, 1, 10, error));  // far more names than needed
  EXPECT_NE(error.find("1000000001"), std::string::npos);
}

TEST(IoTextParsing, NumbersMustBeWholeTokens) {
  EXPECT_EQ(parse_int("42"), 42);
  EXPECT_EQ(parse_int(" -7 "), -7);
  EXPECT_EQ(parse_int("+3"), 3);
  EXPECT_FALSE(parse_int("12abc"));
  EXPECT_FALSE(parse_int("1.5"));
  EXPECT_FALSE(parse_int(""));
  EXPECT_FALSE(parse_int("99999999999999999999999"));
  EXPECT_DOUBLE_EQ(*parse_double("0.9570312"), 0.9570312);
  EXPECT_TRUE(std::isnan(*parse_double("NaN")));
  EXPECT_FALSE(parse_double("1.0x"));
  EXPECT_EQ(*parse_doubles("(1,0,0)", "(),"), (std::vector<double>{1, 0, 0}));
  EXPECT_FALSE(parse_ints("1 2 x"));
  EXPECT_EQ(split_words("  a\tb  c ").size(), 3u);
}

}  // namespace
}  // namespace penumbra

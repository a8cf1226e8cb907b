// Replays every input kept in tests/fuzz/regressions/<harness>/ (the minimized
// findings of scripts/fuzz.sh, one file each, named after what they found)
// through its harness, so that each stays fixed in every build, with or
// without clang. The harnesses run the ordinary reader and parser API.
#include "harness.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <iterator>

namespace penumbra::fuzz {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> kept_inputs(std::string_view harness) {
  std::vector<fs::path> files;
  const fs::path dir = fs::path(PENUMBRA_FUZZ_REGRESSIONS_DIR) / harness;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return files;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.is_regular_file()) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

class FuzzRegressions : public ::testing::TestWithParam<std::string> {};

TEST_P(FuzzRegressions, KeptInputsPass) {
  const Harness& harness = find_harness(GetParam());
  for (const fs::path& file : kept_inputs(harness.name)) {
    SCOPED_TRACE(file.filename().string());
    std::ifstream in(file, std::ios::binary);
    const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    try {
      run_harness(harness, bytes);
    } catch (const HarnessFailure& e) {
      ADD_FAILURE() << e.what();
    }
  }
}

std::vector<std::string> harness_names() {
  std::vector<std::string> names;
  for (const Harness& h : harnesses()) names.emplace_back(h.name);
  return names;
}

INSTANTIATE_TEST_SUITE_P(Harness, FuzzRegressions, ::testing::ValuesIn(harness_names()),
                         [](const auto& info) { return info.param; });

// The oracle itself: an untyped exception is a finding, a typed one is not.
TEST(FuzzHarness, TypedErrorsPassAndOtherExceptionsFail) {
  const std::string truncated = "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 2 2 2\nencoding: raw\n\nxx";
  EXPECT_NO_THROW(run_harness(find_harness("nrrd"), Input(reinterpret_cast<const std::uint8_t*>(truncated.data()),
                                                          truncated.size())));
  const Harness throws_logic_error{"logic", [](Input) { throw std::logic_error("boom"); }, ""};
  EXPECT_THROW(run_harness(throws_logic_error, {}), HarnessFailure);
}

}  // namespace
}  // namespace penumbra::fuzz

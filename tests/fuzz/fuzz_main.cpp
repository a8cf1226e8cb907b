// libFuzzer's entry point for one harness, chosen at build time
// (PENUMBRA_FUZZ_HARNESS names it, see CMakeLists.txt). A HarnessFailure
// aborts, so libFuzzer keeps the input as a crash.
#include "harness.h"

#include <cstdio>
#include <cstdlib>

#define PENUMBRA_FUZZ_CONCAT(a, b) a##b
#define PENUMBRA_FUZZ_FUNCTION(name) PENUMBRA_FUZZ_CONCAT(fuzz_, name)
#define PENUMBRA_FUZZ_STRING(name) #name
#define PENUMBRA_FUZZ_NAME(name) PENUMBRA_FUZZ_STRING(name)

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const penumbra::fuzz::Harness harness{PENUMBRA_FUZZ_NAME(PENUMBRA_FUZZ_HARNESS),
                                               penumbra::fuzz::PENUMBRA_FUZZ_FUNCTION(PENUMBRA_FUZZ_HARNESS), ""};
  try {
    penumbra::fuzz::run_harness(harness, {data, size});
  } catch (const penumbra::fuzz::HarnessFailure& e) {
    std::fprintf(stderr, "%s\n", e.what());
    std::abort();
  }
  return 0;
}

#pragma once
// The fuzz harnesses: one function per reader or parser that feeds it one
// input and checks the outcome. The same functions serve libFuzzer
// (fuzz_main.cpp, built with PENUMBRA_FUZZ=ON) and the GoogleTest suite that
// replays the kept inputs of tests/fuzz/regressions/ in every `make test`
// (regression_test.cpp), so a fixed finding stays fixed without clang.
//
// An input passes when the code under test returns normally or throws one of
// penumbra's typed errors (penumbra::Error: IoError, InvalidScene, ...), the
// errors the CLI turns into exit 2; the server harness passes when the error
// maps to a 4xx. Anything else (another exception, a 5xx) is a finding:
// run_harness() throws HarnessFailure. Crashes, sanitizer reports, hangs and
// huge allocations are caught by libFuzzer itself.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace penumbra::fuzz {

class HarnessFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

using Input = std::span<const std::uint8_t>;

struct Harness {
  std::string_view name;  // the fuzz target fuzz_<name>, the folder regressions/<name>
  void (*run)(Input input);
  std::string_view what;  // one line: what it feeds the input to
};

// Every harness, in a fixed order (harness_registry.cpp; the regression test links it).
const std::vector<Harness>& harnesses();
const Harness& find_harness(std::string_view name);

// Runs the harness on one input; throws HarnessFailure naming the exception
// that escaped (or the status the server answered).
void run_harness(const Harness& harness, Input input);

// The memory budget every harness runs under (1 GiB): far below libFuzzer's
// 2 GB malloc limit, so an allocation the budget checks can never trip that
// limit, and one it misses can.
inline constexpr std::uint64_t kFuzzMemoryBudget = std::uint64_t(1) << 30;

// The folder the harnesses read from: the input file and the companion files
// headers may name (docs/RELIABILITY.md lists them), made once per process.
const std::filesystem::path& fixture_dir();

// Writes `input` as fixture_dir()/name and returns the path.
std::filesystem::path write_input(std::string_view name, Input input);

// Harnesses of each group (harness_volumes.cpp, harness_scene.cpp, harness_server.cpp).
void fuzz_nrrd(Input input);
void fuzz_metaimage(Input input);
void fuzz_nifti(Input input);
void fuzz_vti(Input input);
void fuzz_dat(Input input);
void fuzz_scene(Input input);
void fuzz_obj(Input input);
void fuzz_ply(Input input);
void fuzz_preset(Input input);
void fuzz_server(Input input);

}  // namespace penumbra::fuzz

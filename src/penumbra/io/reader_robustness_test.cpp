// Damaged files never crash, hang or assert: valid files from every writer
// are truncated and have bytes overwritten at many places, and every read
// must either succeed or throw IoError / OutOfMemoryBudget.
#include "penumbra/base/memory_budget.h"
#include "penumbra/base/rng.h"
#include "penumbra/io/io_test_support.h"
#include "penumbra/io/volume_reader.h"
#include "penumbra/io/volume_writer.h"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

namespace penumbra {
namespace {

std::vector<std::byte> file_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  const std::vector<char> chars((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::vector<std::byte> bytes(chars.size());
  std::memcpy(bytes.data(), chars.data(), chars.size());
  return bytes;
}

class BudgetGuard {
 public:
  explicit BudgetGuard(std::uint64_t bytes) : previous_(memory_budget_bytes()) { set_memory_budget_bytes(bytes); }
  ~BudgetGuard() { set_memory_budget_bytes(previous_); }

 private:
  std::uint64_t previous_;
};

void read_expecting_no_crash(const std::filesystem::path& path, std::uint64_t& failures) {
  try {
    read_volume(path);
  } catch (const IoError&) {
    ++failures;
  } catch (const OutOfMemoryBudget&) {
    ++failures;
  }
  // Anything else escapes and fails the test.
}

TEST(IoRobustness, DamagedFilesGiveTypedErrorsNeverCrashes) {
  test::TempDir dir;
  // Damage can turn a size field into something huge; keep what may be
  // allocated small.
  BudgetGuard budget(std::uint64_t(64) << 20);
  const auto volume = test::make_volume(ivec3(9, 7, 5), VoxelType::Int16, 2);
  struct Original {
    std::string name;
    std::function<void(const std::filesystem::path&)> write;
  };
  const std::vector<Original> originals = {
      {"raw.nrrd", [&](const auto& p) { write_nrrd(p, *volume, false, std::endian::big); }},
      {"gz.nrrd", [&](const auto& p) { write_nrrd(p, *volume, true); }},
      {"raw.mha", [&](const auto& p) { write_metaimage(p, *volume, false); }},
      {"zlib.mha", [&](const auto& p) { write_metaimage(p, *volume, true, std::endian::big); }},
      {"ascii.vti", [&](const auto& p) { write_vti(p, *volume, {VtiFormat::Ascii}); }},
      {"binary.vti", [&](const auto& p) { write_vti(p, *volume, {VtiFormat::Binary, true, false}); }},
      {"appended.vti", [&](const auto& p) { write_vti(p, *volume, {VtiFormat::AppendedRaw, true}); }},
      {"appended64.vti", [&](const auto& p) { write_vti(p, *volume, {VtiFormat::AppendedBase64, false}); }},
      {"v.nii", [&](const auto& p) {
         test::write_file(p, test::NiftiHeader(std::endian::big).dims({9, 7, 5, 2}).datatype(4)
                                 .file(test::voxel_file_bytes(*volume, std::endian::big)));
       }},
      {"v.nii.gz", [&](const auto& p) {
         test::write_file(p, test::gzip(test::NiftiHeader(std::endian::little).dims({9, 7, 5, 2}).datatype(4)
                                            .scaling(2.0f, 1.0f)
                                            .file(test::voxel_file_bytes(*volume, std::endian::little))));
       }},
      {"v.dat", [&](const auto& p) {
         test::write_file(dir / "v.raw", test::voxel_file_bytes(*volume, std::endian::little));
         test::write_file(p, "ObjectFileName: v.raw\nResolution: 9 7 5 2\nSliceThickness: 1 2 3\nFormat: SHORT\n");
       }},
  };
  // --gtest_random_seed=N explores other damage.
  Pcg32 rng(12345 + std::uint64_t(::testing::UnitTest::GetInstance()->random_seed()));
  std::uint64_t failures = 0;
  for (const Original& original : originals) {
    SCOPED_TRACE(original.name);
    const auto source = dir / ("original_" + original.name);
    original.write(source);
    const std::vector<std::byte> bytes = file_bytes(source);
    const auto damaged = dir / original.name;
    // Truncations.
    for (int i = 0; i < 40; ++i) {
      const std::size_t keep = static_cast<std::size_t>(rng.next_float() * float(bytes.size()));
      test::write_file(damaged, std::span(bytes).first(keep));
      read_expecting_no_crash(damaged, failures);
    }
    // Overwritten bytes, in the header more often than in the voxels.
    for (int i = 0; i < 200; ++i) {
      std::vector<std::byte> copy = bytes;
      const int edits = 1 + int(rng.next_float() * 4.0f);
      for (int e = 0; e < edits; ++e) {
        const float where = rng.next_float();
        const std::size_t at = static_cast<std::size_t>((i % 2 ? where * 400.0f : where * float(copy.size()))) %
                               copy.size();
        static constexpr char kInteresting[] = {'0', '9', '-', ' ', '\n', '\0', '%', '(', '<', '"', '=', ':', '\xff'};
        copy[at] = rng.next_float() < 0.5f ? std::byte(kInteresting[int(rng.next_float() * 13.0f) % 13])
                                           : std::byte(int(rng.next_float() * 256.0f) & 255);
      }
      test::write_file(damaged, copy);
      read_expecting_no_crash(damaged, failures);
    }
  }
  EXPECT_GT(failures, 0u);
}

}  // namespace
}  // namespace penumbra

#include "harness.h"

#include "penumbra/base/error.h"
#include "penumbra/base/memory_budget.h"
#include "penumbra/base/parallel.h"
#include "penumbra/io/compression.h"
#include "penumbra/io/volume_writer.h"
#include "penumbra/volume/volume.h"

#include <fmt/format.h>

#include <cstring>
#include <fstream>

#include <unistd.h>

namespace penumbra::fuzz {
namespace fs = std::filesystem;

void run_harness(const Harness& harness, Input input) {
  set_memory_budget_bytes(kFuzzMemoryBudget);
  set_thread_count(1);  // deterministic, and one worker as libFuzzer runs
  try {
    harness.run(input);
  } catch (const HarnessFailure&) {
    throw;
  } catch (const Error&) {
    // A typed error names the file, key or parameter: the expected outcome.
  } catch (const std::exception& e) {
    throw HarnessFailure(fmt::format("fuzz_{}: untyped exception escaped: {}", harness.name, e.what()));
  } catch (...) {
    throw HarnessFailure(fmt::format("fuzz_{}: unknown exception escaped", harness.name));
  }
}

namespace {

void write_bytes(const fs::path& path, std::span<const std::byte> bytes) {
  std::error_code ec;
  fs::remove(path, ec);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (!out) throw std::runtime_error("fuzz: cannot write " + path.string());
}

void write_text(const fs::path& path, std::string_view text) {
  write_bytes(path, std::as_bytes(std::span(text.data(), text.size())));
}

// Companions that headers may name: raw, gzip and zlib payloads, slices for
// file patterns and lists, and a small volume, mesh and preset for scenes.
void make_fixtures(const fs::path& dir) {
  fs::create_directories(dir);
  std::vector<std::byte> raw(8192);
  for (std::size_t i = 0; i < raw.size(); ++i) raw[i] = std::byte((i * 37 + i / 251) & 0xff);
  write_bytes(dir / "data.raw", raw);
  write_bytes(dir / "data.raw.gz", deflate_bytes(raw, CompressionFormat::Gzip));
  write_bytes(dir / "data.zraw", deflate_bytes(raw, CompressionFormat::Zlib));
  for (int i = 0; i < 8; ++i) {
    write_bytes(dir / fmt::format("slice{:03d}.raw", i), std::span(raw).subspan(std::size_t(i) * 512, 512));
  }
  Volume volume(ivec3(8, 8, 8), VoxelType::UInt8);
  std::memcpy(volume.frame_data(0), raw.data(), volume.frame_bytes());
  write_nrrd(dir / "volume.nrrd", volume);
  write_text(dir / "mesh.obj",
             "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  write_text(dir / "preset.json",
             R"([{"Name": "Grey", "RGBPoints": [0, 0, 0, 0, 1, 1, 1, 1], "Points": [0, 0, 0.5, 0, 1, 1, 0.5, 0]}])");
}

// Removed at exit, so test runs leave nothing behind.
struct FixtureDir {
  FixtureDir() {
    std::error_code ec;
    const fs::path base = fs::is_directory("/dev/shm", ec) ? fs::path("/dev/shm") : fs::temp_directory_path();
    path = base / fmt::format("penumbra_fuzz_{}", ::getpid());
    make_fixtures(path);
  }
  ~FixtureDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  fs::path path;
};

}  // namespace

const fs::path& fixture_dir() {
  static const FixtureDir dir;
  return dir.path;
}

fs::path write_input(std::string_view name, Input input) {
  const fs::path path = fixture_dir() / name;
  write_bytes(path, std::as_bytes(input));
  return path;
}

}  // namespace penumbra::fuzz

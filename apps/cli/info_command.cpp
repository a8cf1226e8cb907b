// penumbra info FILE: dimensions, voxel type, spacing, origin, time steps,
// value range and a histogram summary of a volume file.
#include "commands.h"

#include "penumbra/io/volume_reader.h"
#include "penumbra/volume/volume.h"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

namespace penumbra::cli {
namespace {

constexpr int kBins = 256;

struct FrameSummary {
  double mean = 0.0;
  double stddev = 0.0;
  std::array<std::uint64_t, kBins> histogram{};
};

FrameSummary summarize(const Volume& volume, int frame, ValueRange range) {
  FrameSummary s;
  const VolumeView v = volume.view(frame);
  const double width = double(range.max) - double(range.min);
  double sum = 0.0, sum_sq = 0.0;
  std::uint64_t count = 0;
  visit_voxel_type(v.type, [&](auto tag) {
    using T = decltype(tag);
    const T* data = static_cast<const T*>(v.data);
    for (std::uint64_t i = 0; i < volume.voxel_count(); ++i) {
      const double x = double(data[i]);
      if (!std::isfinite(x)) continue;
      sum += x;
      sum_sq += x * x;
      ++count;
      const int bin = width > 0.0 ? std::min(kBins - 1, int((x - range.min) / width * kBins)) : 0;
      ++s.histogram[std::size_t(bin)];
    }
    return 0;
  });
  if (count > 0) {
    s.mean = sum / double(count);
    s.stddev = std::sqrt(std::max(0.0, sum_sq / double(count) - s.mean * s.mean));
  }
  return s;
}

void run_info(const std::string& file) {
  const std::shared_ptr<Volume> volume = read_volume(file);
  const ivec3 d = volume->dims();
  const vec3 sp = volume->spacing();
  const vec3 o = volume->origin();
  const ValueRange range = volume->value_range();
  fmt::print("file        {}\n", file);
  fmt::print("dims        {} x {} x {} ({} voxels)\n", d.x, d.y, d.z, volume->voxel_count());
  fmt::print("type        {}\n", to_string(volume->type()));
  fmt::print("spacing     {} {} {}\n", sp.x, sp.y, sp.z);
  fmt::print("origin      {} {} {}\n", o.x, o.y, o.z);
  fmt::print("time steps  {}\n", volume->frame_count());
  fmt::print("bytes       {} ({:.1f} MiB)\n", volume->total_bytes(), double(volume->total_bytes()) / (1 << 20));
  fmt::print("value range {} .. {}\n", range.min, range.max);
  if (range.non_finite > 0) fmt::print("non-finite  {} voxels (NaN/inf: rendered transparent)\n", range.non_finite);

  std::array<std::uint64_t, kBins> histogram{};
  for (int f = 0; f < volume->frame_count(); ++f) {
    const FrameSummary s = summarize(*volume, f, range);
    for (int b = 0; b < kBins; ++b) histogram[std::size_t(b)] += s.histogram[std::size_t(b)];
    if (volume->frame_count() > 1 || f == 0) {
      fmt::print("{}mean {:.4g}  std {:.4g}\n", volume->frame_count() > 1 ? fmt::format("frame {:<5} ", f) : "",
                 s.mean, s.stddev);
    }
  }
  std::uint64_t total = 0;
  for (auto c : histogram) total += c;
  if (total == 0) return;
  // Percentiles to the resolution of the 256-bin histogram.
  const double width = double(range.max) - double(range.min);
  fmt::print("percentiles (to 1/256 of the range):");
  for (double p : {1.0, 5.0, 25.0, 50.0, 75.0, 95.0, 99.0}) {
    std::uint64_t acc = 0;
    int bin = 0;
    while (bin < kBins - 1 && double(acc + histogram[std::size_t(bin)]) < p / 100.0 * double(total)) {
      acc += histogram[std::size_t(bin)];
      ++bin;
    }
    fmt::print(" p{:g}={:.4g}", p, range.min + width * (bin + 0.5) / kBins);
  }
  fmt::print("\nhistogram (16 bins, log scale):\n");
  std::array<std::uint64_t, 16> coarse{};
  for (int b = 0; b < kBins; ++b) coarse[std::size_t(b / 16)] += histogram[std::size_t(b)];
  double max_log = 0.0;
  for (auto c : coarse) max_log = std::max(max_log, std::log10(1.0 + double(c)));
  for (int b = 0; b < 16; ++b) {
    const double lo = range.min + width * b / 16.0;
    const int bar = max_log > 0.0 ? int(std::round(40.0 * std::log10(1.0 + double(coarse[std::size_t(b)])) / max_log)) : 0;
    fmt::print("  {:>10.4g} {:>11} {}\n", lo, coarse[std::size_t(b)], std::string(std::size_t(bar), '#'));
  }
}

}  // namespace

void add_info_command(CLI::App& app) {
  auto file = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand("info", "describe a volume file: dims, type, spacing, value range, histogram");
  cmd->add_option("file", *file, "volume file (.nrrd .nhdr .mhd .mha .nii .nii.gz .vti .dat)")->required();
  cmd->callback([file] { run_info(*file); });
}

}  // namespace penumbra::cli

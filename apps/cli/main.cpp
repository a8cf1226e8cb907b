// penumbra: command-line front end. `penumbra --help` lists the subcommands.
#include "commands.h"

#include "penumbra/backends/cpu/packets.h"
#include "penumbra/backends/device.h"
#include "penumbra/base/error.h"
#include "penumbra/base/parallel.h"

#include <fmt/format.h>

#include <cstdio>
#include <exception>
#include <string>

int main(int argc, char** argv) {
  CLI::App app{"penumbra: direct volume rendering with advanced illumination"};
  app.require_subcommand(1);
  int threads = 0;
  app.add_option("--threads", threads, "worker threads (0 = all cores)")->check(CLI::NonNegativeNumber);
  std::string simd = "auto";
  app.add_option("--simd", simd,
                 "packet path of the shared marching loop: auto (the widest this CPU has), off (one ray at a time), "
                 "avx2 (8 rays), avx512 (16 rays)");
  std::string device = "auto";
  app.add_option("--device", device,
                 "where techniques with a CUDA path render: auto (cuda when this build has the backend and a GPU is "
                 "present), cpu, cuda");
  app.parse_complete_callback([&] {
    penumbra::set_thread_count(threads);
    penumbra::set_simd_mode(penumbra::parse_simd_mode(simd));
    penumbra::set_device_mode(penumbra::parse_device_mode(device));
  });
  penumbra::cli::add_render_command(app);
  penumbra::cli::add_info_command(app);
  penumbra::cli::add_techniques_command(app);
  penumbra::cli::add_bench_command(app);
  penumbra::cli::add_compare_command(app);
  penumbra::cli::add_serve_command(app);
  penumbra::cli::add_plot_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  } catch (const penumbra::Error& e) {
    fmt::print(stderr, "penumbra: error: {}\n", e.what());
    return 2;
  } catch (const std::bad_alloc&) {
    fmt::print(stderr, "penumbra: error: out of memory\n");
    return 2;
  } catch (const std::exception& e) {
    fmt::print(stderr, "penumbra: internal error: {}\n", e.what());
    return 3;
  }
  return 0;
}

#pragma once
// The penumbra subcommands; each adds itself to the app and runs from its
// callback. Errors are thrown and reported by main() (exit code 2).
#include <CLI/CLI.hpp>

namespace penumbra::cli {

void add_render_command(CLI::App& app);
void add_info_command(CLI::App& app);
void add_techniques_command(CLI::App& app);
void add_bench_command(CLI::App& app);
void add_compare_command(CLI::App& app);
void add_serve_command(CLI::App& app);
void add_plot_command(CLI::App& app);

}  // namespace penumbra::cli

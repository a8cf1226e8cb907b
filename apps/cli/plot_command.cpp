// penumbra plot: a line plot PNG from a CSV table (analysis/line_plot.h), for
// figures such as docs/comparison-report.md's error against light size
// (scripts/soft-shadow-table.sh). The CSV has a header line "series,x,y" and
// one point per line; a series' points are drawn in file order, series in
// the order they first appear. Blank lines and lines starting with '#' are
// skipped.
#include "cli_common.h"
#include "commands.h"

#include "penumbra/analysis/line_plot.h"
#include "penumbra/base/error.h"
#include "penumbra/io/image_io.h"

#include <fmt/format.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

namespace penumbra::cli {
namespace {

struct PlotOptions {
  std::string input, output, title, x_label, y_label, size = "720x420";
};

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r"), e = s.find_last_not_of(" \t\r");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

double parse_number(const std::string& path, int line, const std::string& text, const char* column) {
  const std::string t = trim(text);
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(t.c_str(), &end);
  if (t.empty() || end != t.c_str() + t.size() || errno == ERANGE || !std::isfinite(v)) {
    throw IoError(path, fmt::format("line {}: column {} is not a finite number: '{}'", line, column, t));
  }
  return v;
}

std::vector<PlotSeries> read_plot_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw IoError(path, "cannot open the CSV file");
  std::vector<PlotSeries> series;
  std::map<std::string, std::size_t> index;
  std::string text;
  int line = 0;
  bool header = false;
  constexpr std::size_t kMaxPoints = 1000000;
  std::size_t points = 0;
  while (std::getline(in, text)) {
    ++line;
    const std::string t = trim(text);
    if (t.empty() || t[0] == '#') continue;
    std::vector<std::string> cells;
    std::stringstream cells_in(t);
    for (std::string cell; std::getline(cells_in, cell, ',');) cells.push_back(trim(cell));
    if (!header) {
      if (cells != std::vector<std::string>{"series", "x", "y"}) {
        throw IoError(path, fmt::format("line {}: the header must be 'series,x,y'", line));
      }
      header = true;
      continue;
    }
    if (cells.size() != 3) throw IoError(path, fmt::format("line {}: expected 3 columns, got {}", line, cells.size()));
    if (cells[0].empty()) throw IoError(path, fmt::format("line {}: empty series name", line));
    if (++points > kMaxPoints) throw IoError(path, fmt::format("more than {} points", kMaxPoints));
    const vec2 p(float(parse_number(path, line, cells[1], "x")), float(parse_number(path, line, cells[2], "y")));
    auto [it, added] = index.emplace(cells[0], series.size());
    if (added) series.push_back(PlotSeries{cells[0], {}});
    series[it->second].points.push_back(p);
  }
  if (!header) throw IoError(path, "no header line 'series,x,y'");
  if (series.empty()) throw IoError(path, "no data lines");
  return series;
}

void run_plot(const PlotOptions& o) {
  LinePlot plot;
  plot.series = read_plot_csv(o.input);
  plot.title = o.title;
  plot.x_label = o.x_label;
  plot.y_label = o.y_label;
  std::tie(plot.width, plot.height) = parse_size(o.size);
  write_png(o.output, draw_line_plot(plot));
}

}  // namespace

void add_plot_command(CLI::App& app) {
  auto options = std::make_shared<PlotOptions>();
  CLI::App* cmd = app.add_subcommand("plot", "draw a line plot PNG from a CSV table with columns series,x,y");
  cmd->add_option("data", options->input, "CSV file: header 'series,x,y', one point per line")->required();
  cmd->add_option("-o,--output", options->output, "output PNG")->required();
  cmd->add_option("--title", options->title, "title above the plot");
  cmd->add_option("--x-label", options->x_label, "label of the x axis");
  cmd->add_option("--y-label", options->y_label, "label of the y axis");
  cmd->add_option("--size", options->size, "image size WxH (default 720x420)");
  cmd->callback([options] { run_plot(*options); });
}

}  // namespace penumbra::cli

#include "penumbra/analysis/line_plot.h"

#include "penumbra/analysis/color_space.h"
#include "penumbra/analysis/text.h"
#include "penumbra/base/error.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace penumbra {
namespace {

// Ten colours far apart in hue and lightness (sRGB bytes).
constexpr unsigned char kPalette[10][3] = {{31, 100, 180}, {240, 120, 20},  {40, 150, 50},  {210, 40, 40},
                                           {140, 90, 190}, {130, 80, 60},   {220, 110, 180}, {110, 110, 110},
                                           {180, 180, 30}, {20, 180, 200}};

const vec3 kInk = srgb_decode(vec3(0.1f));
const vec3 kGrid = srgb_decode(vec3(0.88f));

void put(Image& image, int x, int y, vec3 color) {
  if (x >= 0 && y >= 0 && x < image.width() && y < image.height()) image.at(x, y) = vec4(color, 1.0f);
}

void fill_rect(Image& image, int x0, int y0, int x1, int y1, vec3 color) {
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) put(image, x, y, color);
  }
}

// A segment `thickness` pixels wide (a square brush stepped along it).
void draw_segment(Image& image, vec2 a, vec2 b, vec3 color, int thickness) {
  const float length = glm::length(b - a);
  const int steps = std::max(1, int(std::ceil(length * 2.0f)));
  const int lo = -(thickness - 1) / 2, hi = thickness / 2;
  for (int i = 0; i <= steps; ++i) {
    const vec2 p = a + (b - a) * (float(i) / float(steps));
    const int x = int(std::lround(p.x)), y = int(std::lround(p.y));
    fill_rect(image, x + lo, y + lo, x + hi, y + hi, color);
  }
}

void draw_marker(Image& image, vec2 p, vec3 color, bool hollow) {
  const int x = int(std::lround(p.x)), y = int(std::lround(p.y));
  fill_rect(image, x - 3, y - 3, x + 3, y + 3, color);
  if (hollow) fill_rect(image, x - 1, y - 1, x + 1, y + 1, vec3(1.0f));
}

std::string tick_label(double v, double step) {
  // Enough decimals to tell neighbouring ticks apart.
  const int decimals = std::max(0, -int(std::floor(std::log10(step) + 1e-9)));
  return fmt::format("{:.{}f}", std::abs(v) < 0.5 * step ? 0.0 : v, decimals);
}

}  // namespace

vec3 plot_color(std::size_t i) {
  const unsigned char* c = kPalette[i % 10];
  return srgb_decode(vec3(c[0], c[1], c[2]) / 255.0f);
}

std::vector<double> plot_ticks(double lo, double hi, int max_ticks) {
  if (!std::isfinite(lo) || !std::isfinite(hi) || lo > hi) {
    throw InvalidArgument("range", fmt::format("plot axis range [{}, {}] is not an interval", lo, hi));
  }
  if (max_ticks < 2) throw InvalidArgument("max_ticks", "must be at least 2");
  if (lo == hi) {
    lo -= 0.5;
    hi += 0.5;
  }
  const double raw = (hi - lo) / double(max_ticks - 1);
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  // The finest step whose whole multiples covering [lo, hi] number at most
  // max_ticks (the slack keeps a bound that is a multiple from rounding up).
  double step = power, first = 0.0, last = 0.0;
  for (double m : {1.0, 2.0, 5.0, 10.0, 20.0}) {
    step = m * power;
    first = std::floor(lo / step + 1e-9);
    last = std::ceil(hi / step - 1e-9);
    if (last - first + 1.0 <= double(max_ticks)) break;
  }
  std::vector<double> ticks;
  for (double k = first; k <= last; k += 1.0) ticks.push_back(k * step);
  return ticks;
}

Image draw_line_plot(const LinePlot& plot) {
  if (plot.width < 240 || plot.height < 160 || plot.width > 8192 || plot.height > 8192) {
    throw InvalidArgument("size", fmt::format("a plot must be 240x160 to 8192x8192 pixels, got {}x{}", plot.width,
                                              plot.height));
  }
  if (plot.series.empty()) throw InvalidArgument("series", "a plot needs at least one series");
  double x_lo = std::numeric_limits<double>::max(), x_hi = -x_lo, y_lo = x_lo, y_hi = -x_lo;
  for (const PlotSeries& s : plot.series) {
    if (s.points.empty()) throw InvalidArgument(s.name, "the series has no points");
    for (vec2 p : s.points) {
      if (!std::isfinite(p.x) || !std::isfinite(p.y)) throw InvalidArgument(s.name, "a point is not finite");
      x_lo = std::min(x_lo, double(p.x));
      x_hi = std::max(x_hi, double(p.x));
      y_lo = std::min(y_lo, double(p.y));
      y_hi = std::max(y_hi, double(p.y));
    }
  }
  if (y_lo >= 0.0) y_lo = 0.0;
  const std::vector<double> xt = plot_ticks(x_lo, x_hi), yt = plot_ticks(y_lo, y_hi);
  const double x0 = xt.front(), x1 = xt.back(), y0 = yt.front(), y1 = yt.back();

  // Layout: title on top, y labels left, x labels below, legend right.
  int legend_width = 0;
  for (const PlotSeries& s : plot.series) legend_width = std::max(legend_width, text_width(s.name));
  legend_width += 30;
  int y_label_width = 0;
  for (double v : yt) y_label_width = std::max(y_label_width, text_width(tick_label(v, yt[1] - yt[0])));
  const int left = y_label_width + 12 + (plot.y_label.empty() ? 0 : kLineAdvance + 4);
  const int top = plot.title.empty() ? 12 : 12 + 2 * kLineAdvance;
  const int right = plot.width - legend_width - 12;
  const int bottom = plot.height - (plot.x_label.empty() ? 24 : 24 + kLineAdvance + 4);
  if (right - left < 60 || bottom - top < 60) {
    throw InvalidArgument("size", "the plot is too small for its labels and legend");
  }
  auto to_pixel = [&](vec2 p) {
    return vec2(float(left + (double(p.x) - x0) / (x1 - x0) * (right - left)),
                float(bottom - (double(p.y) - y0) / (y1 - y0) * (bottom - top)));
  };

  Image image(plot.width, plot.height, vec4(1.0f));
  for (double v : xt) {
    const int x = int(std::lround(to_pixel(vec2(float(v), float(y0))).x));
    fill_rect(image, x, top, x, bottom, kGrid);
    const std::string label = tick_label(v, xt[1] - xt[0]);
    draw_text(image, x - text_width(label) / 2, bottom + 6, label, kInk);
  }
  for (double v : yt) {
    const int y = int(std::lround(to_pixel(vec2(float(x0), float(v))).y));
    fill_rect(image, left, y, right, y, kGrid);
    const std::string label = tick_label(v, yt[1] - yt[0]);
    draw_text(image, left - 6 - text_width(label), y - kGlyphHeight / 2, label, kInk);
  }
  fill_rect(image, left, top, left, bottom, kInk);
  fill_rect(image, left, bottom, right, bottom, kInk);
  if (!plot.title.empty()) draw_text(image, (left + right - text_width(plot.title)) / 2, 10, plot.title, kInk);
  if (!plot.x_label.empty()) {
    draw_text(image, (left + right - text_width(plot.x_label)) / 2, plot.height - kLineAdvance - 6, plot.x_label,
              kInk);
  }
  if (!plot.y_label.empty()) {
    // Vertical text, one character per line, centred on the axis.
    std::string column;
    for (char c : plot.y_label) {
      column += c;
      column += '\n';
    }
    column.pop_back();
    draw_text(image, 4, std::max(top, (top + bottom - text_height(column)) / 2), column, kInk);
  }
  for (std::size_t i = 0; i < plot.series.size(); ++i) {
    const PlotSeries& s = plot.series[i];
    const vec3 color = plot_color(i);
    const bool hollow = i >= 10;
    for (std::size_t j = 1; j < s.points.size(); ++j) {
      draw_segment(image, to_pixel(s.points[j - 1]), to_pixel(s.points[j]), color, 2);
    }
    for (vec2 p : s.points) draw_marker(image, to_pixel(p), color, hollow);
    const int ly = top + int(i) * (kLineAdvance + 6) + 4;
    draw_segment(image, vec2(float(right + 14), float(ly + 3)), vec2(float(right + 30), float(ly + 3)), color, 2);
    draw_marker(image, vec2(float(right + 22), float(ly + 3)), color, hollow);
    draw_text(image, right + 36, ly, s.name, kInk);
  }
  return image;
}

}  // namespace penumbra

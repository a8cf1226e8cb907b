#include "penumbra/techniques/pathtrace/progress_bar.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <unistd.h>

namespace penumbra {

ProgressBar::ProgressBar(std::string label, bool enabled)
    : label_(std::move(label)), active_(enabled && isatty(fileno(stderr)) != 0), start_(Clock::now()),
      last_draw_(start_) {}

ProgressBar::~ProgressBar() {
  if (!active_) return;
  const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
  fmt::print(stderr, "\r{}\n", line(label_, 1.0, elapsed));
}

void ProgressBar::update(double fraction) {
  if (!active_) return;
  std::unique_lock lock(mutex_, std::try_to_lock);
  if (!lock.owns_lock()) return;  // another thread is drawing
  const Clock::time_point now = Clock::now();
  if (now - last_draw_ < std::chrono::milliseconds(100)) return;
  last_draw_ = now;
  fmt::print(stderr, "\r{}", line(label_, fraction, std::chrono::duration<double>(now - start_).count()));
  std::fflush(stderr);
}

std::string ProgressBar::line(const std::string& label, double fraction, double elapsed_s, int bar_width) {
  fraction = std::clamp(fraction, 0.0, 1.0);
  const int filled = static_cast<int>(fraction * bar_width + 0.5);
  std::string text = fmt::format("{} [{}{}] {:3.0f}%  {:.1f} s", label, std::string(std::size_t(filled), '#'),
                                 std::string(std::size_t(bar_width - filled), '-'), 100.0 * fraction, elapsed_s);
  // The estimate needs some progress to mean anything.
  if (fraction > 0.02 && fraction < 1.0) {
    text += fmt::format(", ~{:.1f} s left", elapsed_s * (1.0 - fraction) / fraction);
  }
  return text + "   ";  // clears the tail of a longer previous line
}

}  // namespace penumbra

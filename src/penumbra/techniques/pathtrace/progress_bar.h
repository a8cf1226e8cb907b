#pragma once
// A one-line progress bar on stderr for long renders, drawn only when stderr
// is a terminal (logs and pipes stay clean). Host code only.
#include <chrono>
#include <mutex>
#include <string>

namespace penumbra {

class ProgressBar {
 public:
  // Draws nothing unless `enabled` and stderr is a terminal.
  ProgressBar(std::string label, bool enabled);
  ~ProgressBar();  // ends the line
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  bool active() const { return active_; }
  // Thread-safe; redraws at most every 100 ms. `fraction` in [0, 1].
  void update(double fraction);

  // The text of one update, e.g. "pathtrace [#####-----]  50%  1.2 s, ~1.2 s left".
  static std::string line(const std::string& label, double fraction, double elapsed_s, int bar_width = 30);

 private:
  using Clock = std::chrono::steady_clock;
  std::string label_;
  bool active_ = false;
  Clock::time_point start_;
  Clock::time_point last_draw_;
  std::mutex mutex_;
};

}  // namespace penumbra

#include "penumbra/techniques/pathtrace/progress_bar.h"

#include <gtest/gtest.h>

namespace penumbra {
namespace {

TEST(ProgressBar, LineShowsFractionElapsedAndEstimate) {
  EXPECT_EQ(ProgressBar::line("pt", 0.5, 2.0, 10), "pt [#####-----]  50%  2.0 s, ~2.0 s left   ");
  EXPECT_EQ(ProgressBar::line("pt", 0.0, 0.0, 4), "pt [----]   0%  0.0 s   ");
  EXPECT_EQ(ProgressBar::line("pt", 1.7, 3.0, 4), "pt [####] 100%  3.0 s   ");  // clamped
}

// ctest runs with stderr redirected, so the bar stays silent; disabled bars
// are silent everywhere.
TEST(ProgressBar, DisabledBarIsInactive) {
  ProgressBar bar("x", false);
  EXPECT_FALSE(bar.active());
  bar.update(0.5);
}

}  // namespace
}  // namespace penumbra

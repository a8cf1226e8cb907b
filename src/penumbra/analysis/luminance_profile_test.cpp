#include "penumbra/analysis/luminance_profile.h"

#include "penumbra/base/error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace penumbra {
namespace {

std::vector<float> cosine(int n, int cycles, float amplitude, float phase, float offset) {
  std::vector<float> signal(std::size_t(n), 0.0f);
  for (int i = 0; i < n; ++i) {
    signal[std::size_t(i)] = offset + amplitude * std::cos(2.0f * kPi * float(cycles * i) / float(n) + phase);
  }
  return signal;
}

TEST(LuminanceProfile, RowLuminanceReadsOneRowLeftToRight) {
  Image image(3, 2, vec4(0.0f));
  image.at(0, 1) = vec4(1.0f, 0.0f, 0.0f, 1.0f);
  image.at(2, 1) = vec4(0.0f, 0.0f, 1.0f, 1.0f);
  const std::vector<float> row = row_luminance(image, 1);
  ASSERT_EQ(row.size(), 3u);
  EXPECT_FLOAT_EQ(row[0], 0.2126f);
  EXPECT_FLOAT_EQ(row[1], 0.0f);
  EXPECT_FLOAT_EQ(row[2], 0.0722f);
  EXPECT_THROW(row_luminance(image, 2), InvalidArgument);
  EXPECT_THROW(row_luminance(image, -1), InvalidArgument);
}

TEST(LuminanceProfile, CosineOfKCyclesPeaksAtBinK) {
  for (const int n : {64, 100, 257}) {
    for (const int k : {1, 5, 17, 31}) {
      const std::vector<float> spectrum = amplitude_spectrum(cosine(n, k, 0.25f, 0.7f, 0.5f));
      ASSERT_EQ(spectrum.size(), std::size_t(n / 2 + 1));
      const auto peak = std::max_element(spectrum.begin() + 1, spectrum.end()) - spectrum.begin();
      EXPECT_EQ(peak, k) << "n " << n;
      EXPECT_NEAR(spectrum[std::size_t(k)], 0.25f, 1e-4f);
      EXPECT_NEAR(spectrum[0], 0.5f, 1e-4f);  // the mean
      for (std::size_t bin = 1; bin < spectrum.size(); ++bin) {
        if (int(bin) != k) {
          EXPECT_LT(spectrum[bin], 1e-4f) << "n " << n << " k " << k << " bin " << bin;
        }
      }
    }
  }
}

TEST(LuminanceProfile, NyquistAndEmptySignals) {
  std::vector<float> alternating;
  for (int i = 0; i < 16; ++i) alternating.push_back(i % 2 == 0 ? 1.0f : -1.0f);
  EXPECT_NEAR(amplitude_spectrum(alternating)[8], 1.0f, 1e-6f);
  EXPECT_TRUE(amplitude_spectrum({}).empty());
  EXPECT_EQ(amplitude_spectrum({3.0f}), std::vector<float>{3.0f});
}

}  // namespace
}  // namespace penumbra

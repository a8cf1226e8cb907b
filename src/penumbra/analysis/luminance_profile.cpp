#include "penumbra/analysis/luminance_profile.h"

#include "penumbra/base/error.h"

#include <fmt/format.h>

#include <cmath>

namespace penumbra {

std::vector<float> row_luminance(const Image& image, int row) {
  if (row < 0 || row >= image.height()) {
    throw InvalidArgument("row", fmt::format("row {} is outside a {}x{} image", row, image.width(), image.height()));
  }
  std::vector<float> profile(std::size_t(image.width()));
  for (int x = 0; x < image.width(); ++x) profile[std::size_t(x)] = luminance(vec3(image.at(x, row)));
  return profile;
}

std::vector<float> amplitude_spectrum(const std::vector<float>& signal) {
  const std::size_t n = signal.size();
  if (n == 0) return {};
  // One table of n angles instead of cos(2 pi j k / n) per term: the index
  // j k mod n is exact, so large j k lose no accuracy.
  std::vector<double> cos_table(n), sin_table(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double angle = 2.0 * 3.14159265358979323846 * double(i) / double(n);
    cos_table[i] = std::cos(angle);
    sin_table[i] = std::sin(angle);
  }
  std::vector<float> amplitudes(n / 2 + 1);
  for (std::size_t k = 0; k < amplitudes.size(); ++k) {
    double re = 0.0, im = 0.0;
    std::size_t index = 0;  // j k mod n
    for (std::size_t j = 0; j < n; ++j) {
      re += double(signal[j]) * cos_table[index];
      im -= double(signal[j]) * sin_table[index];
      index += k;
      if (index >= n) index -= n;
    }
    const bool unpaired = k == 0 || 2 * k == n;  // bins without a mirror image
    amplitudes[k] = static_cast<float>(std::hypot(re, im) * (unpaired ? 1.0 : 2.0) / double(n));
  }
  return amplitudes;
}

}  // namespace penumbra

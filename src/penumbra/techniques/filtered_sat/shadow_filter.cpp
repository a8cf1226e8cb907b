#include "penumbra/techniques/filtered_sat/shadow_filter.h"

#include <cmath>

namespace penumbra {

ShadowFilter make_shadow_filter(FilterKernel kernel, float width, float density_scale, float offset) {
  ShadowFilter f;
  f.density_scale = density_scale;
  f.offset = offset * 0.5f * width;
  if (kernel == FilterKernel::Box) {
    f.half_width = 0.5f * width;
    return f;
  }
  // Weights from the Gaussian's mass over each tap (support +-3 sigma); in
  // units of sigma first, then scaled so that the kernel as applied (each
  // tap's weight spread evenly over its sub-patch) has the box's variance
  // w^2 / 12 exactly.
  constexpr double kSupport = 3.0;
  f.taps = ShadowFilter::kMaxTaps;
  const double step = 2.0 * kSupport / f.taps;
  auto cdf = [](double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); };
  const double total = cdf(kSupport) - cdf(-kSupport);
  double variance = 0.0;  // of the applied kernel, in units of sigma^2
  for (int i = 0; i < f.taps; ++i) {
    const double a = -kSupport + i * step;
    f.weights[i] = float((cdf(a + step) - cdf(a)) / total);
    const double centre = a + 0.5 * step;
    variance += f.weights[i] * (centre * centre + step * step / 12.0);
  }
  const double sigma = double(width) / std::sqrt(12.0 * variance);
  f.half_width = float(kSupport * sigma);
  return f;
}

}  // namespace penumbra

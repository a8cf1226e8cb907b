#include "penumbra/analysis/image_metrics.h"

#include "penumbra/base/error.h"
#include "penumbra/base/parallel.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace penumbra {
namespace {

struct PixelErrors {
  double squared_sum = 0.0;
  double absolute_sum = 0.0;
  double absolute_max = 0.0;
  double samples = 0.0;
};

PixelErrors pixel_errors(const Image& test, const Image& reference) {
  check_same_size(test, reference);
  PixelErrors errors;
  const std::vector<vec4>& t = test.pixels();
  const std::vector<vec4>& r = reference.pixels();
  for (std::size_t i = 0; i < t.size(); ++i) {
    for (int channel = 0; channel < 3; ++channel) {
      const double d = double(t[i][channel]) - double(r[i][channel]);
      errors.squared_sum += d * d;
      errors.absolute_sum += std::abs(d);
      // std::max would drop a NaN that arrives second; this keeps it.
      if (!(std::abs(d) <= errors.absolute_max)) errors.absolute_max = std::abs(d);
    }
  }
  errors.samples = 3.0 * double(t.size());
  return errors;
}

double rmse_of(const PixelErrors& e) { return std::sqrt(e.squared_sum / e.samples); }

double psnr_of(const PixelErrors& e) {
  if (e.squared_sum == 0.0) return std::numeric_limits<double>::infinity();
  return 10.0 * std::log10(e.samples / e.squared_sum);  // peak 1: 1 / MSE
}

vec3 clamped_rgb(const vec4& pixel) {
  // clamp01 keeps NaN as NaN, so a broken pixel shows up in the statistics.
  return {clamp01(pixel.r), clamp01(pixel.g), clamp01(pixel.b)};
}

// Linear interpolation between the order statistics around p (n - 1).
double percentile_of_sorted(const std::vector<float>& sorted, double p) {
  const double position = p * double(sorted.size() - 1);
  const std::size_t below = static_cast<std::size_t>(position);
  const std::size_t above = std::min(below + 1, sorted.size() - 1);
  const double weight = position - double(below);
  return double(sorted[below]) + weight * (double(sorted[above]) - double(sorted[below]));
}

}  // namespace

void check_same_size(const Image& test, const Image& reference) {
  if (test.width() != reference.width() || test.height() != reference.height()) {
    throw InvalidArgument("image", fmt::format("cannot compare a {}x{} image with a {}x{} reference", test.width(),
                                               test.height(), reference.width(), reference.height()));
  }
  if (test.empty()) {
    throw InvalidArgument("image", fmt::format("cannot compare empty ({}x{}) images", test.width(), test.height()));
  }
}

double rmse(const Image& test, const Image& reference) { return rmse_of(pixel_errors(test, reference)); }

double psnr(const Image& test, const Image& reference) { return psnr_of(pixel_errors(test, reference)); }

double mean_absolute_error(const Image& test, const Image& reference) {
  const PixelErrors e = pixel_errors(test, reference);
  return e.absolute_sum / e.samples;
}

double max_abs_error(const Image& test, const Image& reference) {
  return pixel_errors(test, reference).absolute_max;
}

std::vector<float> delta_e_2000_per_pixel(const Image& test, const Image& reference) {
  check_same_size(test, reference);
  std::vector<float> delta_e(test.pixel_count());
  const vec4* t = test.data();
  const vec4* r = reference.data();
  parallel_for(
      0, std::int64_t(delta_e.size()),
      [&](std::int64_t first, std::int64_t last) {
        for (std::int64_t i = first; i < last; ++i) {
          delta_e[std::size_t(i)] = static_cast<float>(
              delta_e_2000(srgb_linear_to_lab(clamped_rgb(t[i])), srgb_linear_to_lab(clamped_rgb(r[i]))));
        }
      },
      4096);
  return delta_e;
}

DeltaEStats delta_e_stats(std::vector<float> per_pixel_delta_e) {
  if (per_pixel_delta_e.empty()) {
    throw InvalidArgument("per_pixel_delta_e", "cannot summarise an empty set of colour differences");
  }
  const bool has_nan = std::any_of(per_pixel_delta_e.begin(), per_pixel_delta_e.end(),
                                   [](float v) { return std::isnan(v); });
  if (has_nan) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    return {nan, nan, nan, nan};
  }
  std::sort(per_pixel_delta_e.begin(), per_pixel_delta_e.end());
  double sum = 0.0;
  for (float v : per_pixel_delta_e) sum += v;
  DeltaEStats stats;
  stats.mean = sum / double(per_pixel_delta_e.size());
  stats.median = percentile_of_sorted(per_pixel_delta_e, 0.5);
  stats.p99 = percentile_of_sorted(per_pixel_delta_e, 0.99);
  stats.max = per_pixel_delta_e.back();
  return stats;
}

DeltaEStats delta_e_stats(const Image& test, const Image& reference) {
  return delta_e_stats(delta_e_2000_per_pixel(test, reference));
}

ImageComparison compare_images(const Image& test, const Image& reference) {
  const PixelErrors errors = pixel_errors(test, reference);
  const DeltaEStats delta_e = delta_e_stats(test, reference);
  ImageComparison result;
  result.rmse = rmse_of(errors);
  result.psnr = psnr_of(errors);
  result.mae = errors.absolute_sum / errors.samples;
  result.ssim = ssim(test, reference);
  result.mean_de = delta_e.mean;
  result.median_de = delta_e.median;
  result.p99_de = delta_e.p99;
  result.max_de = delta_e.max;
  return result;
}

}  // namespace penumbra

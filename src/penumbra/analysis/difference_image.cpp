#include "penumbra/analysis/difference_image.h"

#include "penumbra/analysis/image_metrics.h"
#include "penumbra/base/error.h"

#include <fmt/format.h>

#include <cmath>

namespace penumbra {
namespace {

void check_scale(const char* name, float scale) {
  if (!std::isfinite(scale) || !(scale > 0.0f)) {
    throw InvalidArgument(name, fmt::format("must be positive and finite, got {}", scale));
  }
}

}  // namespace

Image make_delta_e_image(const Image& test, const Image& reference, float max_delta_e) {
  check_scale("max_delta_e", max_delta_e);
  const std::vector<float> delta_e = delta_e_2000_per_pixel(test, reference);
  Image false_color(test.width(), test.height());
  for (std::size_t i = 0; i < delta_e.size(); ++i) {
    false_color.data()[i] = vec4(map_color(ColorMap::viridis, delta_e[i] / max_delta_e), 1.0f);
  }
  return append_color_bar(false_color, ColorBar{ColorMap::viridis, 0.0f, max_delta_e, "dE2000"});
}

Image make_signed_luminance_image(const Image& test, const Image& reference, float max_difference) {
  check_scale("max_difference", max_difference);
  check_same_size(test, reference);
  Image false_color(test.width(), test.height());
  for (std::size_t i = 0; i < test.pixel_count(); ++i) {
    const float difference = luminance(vec3(test.data()[i])) - luminance(vec3(reference.data()[i]));
    const float t = 0.5f + 0.5f * difference / max_difference;
    false_color.data()[i] = vec4(map_color(ColorMap::cool_warm, t), 1.0f);
  }
  return append_color_bar(false_color, ColorBar{ColorMap::cool_warm, -max_difference, max_difference, "dY"});
}

}  // namespace penumbra

#include "penumbra/techniques/filtered_sat/shadow_filter.h"

#include <algorithm>
#include <cmath>
#include <limits>

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

float representative_occluder_distance(const Box3& box, vec3 toward_light) {
  // From the centre to the box's boundary along the direction: the nearest
  // of the three slab exits.
  const vec3 half = 0.5f * box.extent();
  float t = std::numeric_limits<float>::max();
  for (int a = 0; a < 3; ++a) {
    if (std::abs(toward_light[a]) > 1e-6f) t = std::min(t, half[a] / std::abs(toward_light[a]));
  }
  return t < std::numeric_limits<float>::max() ? 2.0f * t / 3.0f : 0.0f;
}

LightFilterShape filter_from_light(const Light& light, const Box3& box) {
  LightFilterShape shape;
  const vec3 centre = box.center();
  if (light.type == LightType::Distant && light.angle_deg > 0.0f) {
    const float distance = representative_occluder_distance(box, glm::normalize(-light.direction));
    const float x = std::tan(glm::radians(std::min(light.angle_deg, 89.0f)));
    if (light.profile == LightProfile::Gaussian) {
      // Per-axis spread distance * tan(sigma) on the patch plane (the RMS of
      // the two axes for an anisotropic light); the box of that variance.
      const float y = std::tan(glm::radians(std::min(light.spread_y_deg(), 89.0f)));
      shape.width = std::sqrt(12.0f) * distance * std::sqrt(0.5f * (x * x + y * y));
      shape.gaussian = true;
    } else {
      // The light's disk of radius distance * tan(theta); the box of its
      // per-axis variance R^2 / 4.
      shape.width = std::sqrt(3.0f) * distance * x;
    }
  } else if ((light.type == LightType::Sphere || light.type == LightType::Disk) && light.radius > 0.0f) {
    const vec3 to_light = light.position - centre;
    const float centre_distance = glm::length(to_light);
    if (!(centre_distance > 0.0f)) return shape;
    // Occluders lie between the receiver and the light.
    const float distance =
        std::min(representative_occluder_distance(box, to_light / centre_distance), 0.5f * centre_distance);
    // Similar triangles: the light's disk of radius r at centre_distance -
    // distance from the occluder, seen through it from the receiver.
    const float r = light.radius * distance / (centre_distance - distance);
    shape.width = std::sqrt(3.0f) * r;
  }
  return shape;
}

}  // namespace penumbra

#include "penumbra/render/change_timing.h"

#include <algorithm>
#include <cmath>

namespace penumbra {
namespace {

std::vector<Light> moved_lights(const std::vector<Light>& lights, vec3 center, float degrees) {
  const float a = glm::radians(degrees);
  const mat3 rotation(std::cos(a), std::sin(a), 0.0f, -std::sin(a), std::cos(a), 0.0f, 0.0f, 0.0f, 1.0f);
  std::vector<Light> out = lights;
  for (Light& l : out) {
    l.direction = rotation * l.direction;
    l.position = center + rotation * (l.position - center);
  }
  return out;
}

// The same TF with every opacity 1% lower or higher, so the change is real.
TransferFunction nudged_tf(const TransferFunction& tf, int round) {
  std::vector<TransferFunctionPoint> points = tf.points();
  for (TransferFunctionPoint& p : points) p.alpha = std::min(1.0f, p.alpha * (round % 2 ? 1.01f : 1.0f / 1.01f));
  TransferFunction out(points);
  out.set_range(tf.range());
  out.set_unit_length(tf.unit_length());
  out.set_density_scale(tf.density_scale());
  return out;
}

}  // namespace

double elapsed_ms(Clock::time_point since) {
  return std::chrono::duration<double, std::milli>(Clock::now() - since).count();
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

ChangeTimings time_scene_changes(Technique& technique, Scene& scene, const ParameterValues& params) {
  std::vector<double> tf_ms, light_ms;
  for (int round = 0; round < 3; ++round) {
    scene.set_transfer_function(nudged_tf(scene.transfer_function(), round));
    auto t0 = Clock::now();
    technique.prepare(scene, params);
    tf_ms.push_back(elapsed_ms(t0));
    scene.set_lights(moved_lights(scene.lights(), scene.volume().world_box().center(), 2.0f));
    t0 = Clock::now();
    technique.prepare(scene, params);
    light_ms.push_back(elapsed_ms(t0));
  }
  return ChangeTimings{median(tf_ms), median(light_ms)};
}

}  // namespace penumbra

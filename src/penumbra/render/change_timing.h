#pragma once
// How `penumbra bench`, `penumbra compare` and the Python bindings time the
// costs the papers tabulate: a TF change and a light move (each the median of
// 3 prepare() calls after the change) and frames.
#include "penumbra/render/parameters.h"
#include "penumbra/render/technique.h"
#include "penumbra/scene/scene.h"

#include <chrono>
#include <vector>

namespace penumbra {

using Clock = std::chrono::steady_clock;

double elapsed_ms(Clock::time_point since);
double median(std::vector<double> values);

struct ChangeTimings {
  double tf_change_ms = 0.0;
  double light_move_ms = 0.0;
};

// Times prepare() after every TF opacity is scaled by 1% and after every light
// turns 2 degrees about z (positioned lights about the volume centre), three
// rounds each. Leaves `scene` with the changed TF and lights.
ChangeTimings time_scene_changes(Technique& technique, Scene& scene, const ParameterValues& params);

}  // namespace penumbra

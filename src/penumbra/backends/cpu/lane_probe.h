#pragma once
// Test support: the lane-generic kernels evaluated as packets on a list of
// inputs (lane_probe.cpp, a SIMD unit compiled per target), so
// lanes_test.cpp can compare each one with its scalar instance.
#include "penumbra/render/render_view.h"

namespace penumbra {

struct LaneProbe {
  // inputs
  const RenderView* view = nullptr;  // volume, TF, normals, lights
  const vec3* positions = nullptr;   // index space
  const float* numbers = nullptr;    // arguments of exp (<= 0), log (> 0) and pow (in [0, 1])
  int count = 0;                     // a multiple of 16
  // outputs, count entries each
  float* values = nullptr;       // trilinear samples
  vec3* gradients = nullptr;     // central differences
  vec3* normals = nullptr;       // precomputed normals (view->normals)
  vec4* tf = nullptr;            // (rgb, sigma_t) at the sampled values
  vec3* exp_log_pow = nullptr;   // exp_nonpositive(-x), log_positive(x), pow_unit(x / (1 + x), 7.5)
  vec3* to_light = nullptr;      // sample_light(view->lights[0]) at the world position of the sample
  float* transmittance = nullptr;  // march_transmittance toward view->lights[0]
  // min(numbers, others), max(numbers, others), clamp(numbers, -1, 1), when
  // `others` (count entries) is set
  const float* others = nullptr;
  vec3* min_max_clamp = nullptr;
  // gather4 of `table` at `table_indices` (count entries, each at most the
  // table's size - 4), when `gathered` (count entries) is set; with `view`
  // null only this runs
  const float* table = nullptr;
  const std::int32_t* table_indices = nullptr;
  vec4* gathered = nullptr;
};

namespace N_AVX2 {
void run_lane_probe(const LaneProbe& probe);
}
namespace N_AVX3 {
void run_lane_probe(const LaneProbe& probe);
}

}  // namespace penumbra

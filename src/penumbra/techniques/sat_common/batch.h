#pragma once
// Filling many values from a light's visibility at once. The caches, bricks
// and plane grids of the SAT techniques call their visibility through
// evaluate_batch, so that it may be either a function of one world point
// (the tables are read point by point, in parallel) or a batch evaluator
// that sees every point first: filtered-sat's streamed tables
// (filtered_sat/streamed_table.h) sort the points by their distance from the
// light and build the table one layer at a time past them, which needs the
// whole batch up front.
#include "penumbra/base/math.h"
#include "penumbra/base/parallel.h"

#include <cstdint>
#include <type_traits>

namespace penumbra {

// out[i] = f(point(i)) for i < count, with f either a function of a world
// point or a batch f(count, point, out).
template <class F, class Point> void evaluate_batch(const F& f, std::int64_t count, const Point& point, float* out) {
  if constexpr (std::is_invocable_r_v<float, const F&, vec3>) {
    parallel_for(0, count, [&](std::int64_t first, std::int64_t last) {
      for (std::int64_t i = first; i < last; ++i) out[i] = f(point(i));
    });
  } else {
    f(count, point, out);
  }
}

// The same for a visibility of several lights, f(light, world) or
// f(light, count, point, out).
template <class F, class Point>
void evaluate_light_batch(const F& f, std::size_t light, std::int64_t count, const Point& point, float* out) {
  if constexpr (std::is_invocable_r_v<float, const F&, std::size_t, vec3>) {
    evaluate_batch([&](vec3 p) { return float(f(light, p)); }, count, point, out);
  } else {
    f(light, count, point, out);
  }
}

}  // namespace penumbra

#include "penumbra/techniques/ipsvi/early_termination.h"

#include "penumbra/base/memory_budget.h"
#include "penumbra/base/parallel.h"
#include "penumbra/render/march.h"

#include <algorithm>
#include <atomic>
#include <cmath>

namespace penumbra {
namespace {

// The point of `ray` closest to the line through x along w (unit vectors);
// the predecessor's depth itself where the two are nearly parallel.
float carry_along_light(const Ray& ray, vec3 x, vec3 w, float fallback) {
  const vec3 r = ray.origin - x;
  const float b = glm::dot(ray.direction, w);
  const float denom = 1.0f - b * b;
  if (denom < 1e-4f) return fallback;
  return (b * glm::dot(w, r) - glm::dot(ray.direction, r)) / denom;
}

}  // namespace

void EarlyTermination::compute(const RenderView& view, const Light& light, const ImageLight& image_light,
                               const PixelRect& rect) {
  samples_ = 0;
  active_ = view.ert_threshold < 1.0f && !rect.empty();
  if (!active_) return;
  const int full_w = view.width, full_h = view.height;
  width_ = (full_w + kFactor - 1) / kFactor;
  height_ = (full_h + kFactor - 1) / kFactor;
  const std::uint64_t count = std::uint64_t(width_) * std::uint64_t(height_);
  check_memory_budget("ipsvi early termination maps", checked_product({count, 4, sizeof(float)}));
  front_.assign(count, -kInfinity);
  back_.assign(count, -kInfinity);
  needed_.assign(count, -kInfinity);
  zone_.assign(count, -kInfinity);
  const float coarse = 2.0f * view.step;
  margin_ = 2.0f * coarse;
  const PixelRect low{rect.x0 / kFactor, rect.y0 / kFactor, (rect.x1 + kFactor - 1) / kFactor,
                      (rect.y1 + kFactor - 1) / kFactor};
  auto low_ray = [&](vec2 low_pixel_center) {
    return view.camera.pixel_ray(low_pixel_center.x * float(kFactor), low_pixel_center.y * float(kFactor), full_w,
                                 full_h);
  };

  // Pre-pass: s_f and s_b per low-resolution ray.
  RenderView coarse_view = view;
  coarse_view.step = coarse;
  const float min_transmittance = 1.0f - view.ert_threshold;
  std::atomic<std::uint64_t> total{0};
  with_sampler(view.volume, [&](const auto& sampler) {
    using Sampler = std::decay_t<decltype(sampler)>;
    parallel_for(low.y0, low.y1, [&](std::int64_t first, std::int64_t last) {
      std::uint64_t samples = 0;
      for (std::int64_t y = first; y < last; ++y) {
        for (int x = low.x0; x < low.x1; ++x) {
          const Ray ray = low_ray(vec2(float(x) + 0.5f, float(y) + 0.5f));
          float t_plane = kInfinity;
          nearest_plane(view, ray, kInfinity, t_plane);
          const Interval iv = volume_interval(view, ray, 0.0f, t_plane);
          const std::size_t i = std::size_t(x) + std::size_t(width_) * std::size_t(y);
          if (iv.empty()) continue;
          float last_end = -kInfinity;
          OccupiedRuns runs(view, ray, iv.t0, iv.t1);
          for (float a = 0.0f, b = 0.0f; runs.next(a, b);) last_end = b;
          back_[i] = last_end;
          const SampleGrid grid(iv, coarse, 0.5f);
          const vec3 o = view.volume.index_from_world(ray.origin);
          const vec3 d = ray.direction / view.volume.spacing;
          float transmittance = 1.0f;
          float front = iv.t1;
          SampleCursor cursor(coarse_view, ray, grid);
          int k;
          float t;
          while (cursor.next(k, t)) {
            ++samples;
            const float value = sampler(o + t * d);
            const vec4 c = Sampler::kAlwaysFinite ? view.tf.lookup_finite(value) : view.tf.lookup(value);
            transmittance *= exp_nonpositive(-c.a * grid.length(k));
            if (transmittance <= min_transmittance) {
              front = glm::min(iv.t1, t + margin_);
              break;
            }
          }
          front_[i] = front;
        }
      }
      total.fetch_add(samples, std::memory_order_relaxed);
    });
    return 0;
  });
  samples_ = total.load();

  // The sweep toward the light, zone by zone, lines in reverse order.
  ImageLight low_light = image_light;
  low_light.position /= float(kFactor);
  const SweepPlan plan = make_sweep_plan(low_light, low, 5.0f);
  for (const SweepZone& zone : plan.zones) {
    std::fill(zone_.begin(), zone_.end(), -kInfinity);
    const int other = 1 - zone.axis;
    for (int li = int(zone.lines.size()) - 1; li >= 0; --li) {
      const SweepLine& line = zone.lines[std::size_t(li)];
      const SweepLine* next = li + 1 < int(zone.lines.size()) ? &zone.lines[std::size_t(li) + 1] : nullptr;
      for (int a = line.lo; a <= line.hi; ++a) {
        ivec2 pixel;
        pixel[zone.axis] = line.coordinate;
        pixel[other] = a;
        const vec2 center = vec2(pixel) + vec2(0.5f);
        if (!(zone.weight(center) > 0.0f)) continue;
        const std::size_t i = std::size_t(pixel.x) + std::size_t(width_) * std::size_t(pixel.y);
        float need = front_[i];
        float across = 0.0f;
        if (next && zone.path_crossing(center, next->coordinate, across)) {
          // The predecessor: the better (farther) of the two pixels around the crossing.
          const int b0 = int(std::floor(across - 0.5f));
          float pred = -kInfinity;
          for (int b = b0; b <= b0 + 1; ++b) {
            if (b < next->lo || b > next->hi) continue;
            ivec2 q;
            q[zone.axis] = next->coordinate;
            q[other] = b;
            pred = glm::max(pred, zone_[std::size_t(q.x) + std::size_t(width_) * std::size_t(q.y)]);
          }
          if (is_finite(pred)) {
            vec2 pred_center;
            pred_center[zone.axis] = float(next->coordinate) + 0.5f;
            pred_center[other] = across;
            const vec3 x = low_ray(pred_center).at(pred);
            const vec3 to_light = sample_light(light, x).to_light;
            need = glm::max(need, carry_along_light(low_ray(center), x, to_light, pred));
          }
        }
        const float l = glm::min(back_[i], need);
        zone_[i] = l;
        needed_[i] = glm::max(needed_[i], l);
      }
    }
  }
}

float EarlyTermination::exit_depth(int x, int y) const {
  if (!active_) return kInfinity;
  const float fx = (float(x) + 0.5f) / float(kFactor) - 0.5f;
  const float fy = (float(y) + 0.5f) / float(kFactor) - 0.5f;
  const int x0 = std::clamp(int(std::floor(fx)), 0, width_ - 1), x1 = std::min(x0 + 1, width_ - 1);
  const int y0 = std::clamp(int(std::floor(fy)), 0, height_ - 1), y1 = std::min(y0 + 1, height_ - 1);
  auto at = [&](int i, int j) { return needed_[std::size_t(i) + std::size_t(width_) * std::size_t(j)]; };
  return std::max(std::max(at(x0, y0), at(x1, y0)), std::max(at(x0, y1), at(x1, y1))) + margin_;
}

std::uint64_t EarlyTermination::bytes() const {
  return (front_.size() + back_.size() + needed_.size() + zone_.size()) * sizeof(float);
}

}  // namespace penumbra

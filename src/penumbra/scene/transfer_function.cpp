#include "penumbra/scene/transfer_function.h"

#include "penumbra/base/error.h"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>

namespace penumbra {

TransferFunction::TransferFunction()
    : TransferFunction({TransferFunctionPoint{0.0f, vec3(0.0f), 0.0f}, TransferFunctionPoint{1.0f, vec3(1.0f), 1.0f}}) {}

TransferFunction::TransferFunction(std::vector<TransferFunctionPoint> points) : points_(std::move(points)) {
  if (points_.empty()) throw InvalidArgument("points", "a transfer function needs at least one control point");
  for (std::size_t i = 0; i < points_.size(); ++i) {
    const TransferFunctionPoint& p = points_[i];
    if (!is_finite(p.value) || !is_finite(p.color.r) || !is_finite(p.color.g) || !is_finite(p.color.b)) {
      throw InvalidArgument(fmt::format("points[{}]", i), "value and colour must be finite numbers");
    }
    if (!(p.alpha >= 0.0f && p.alpha <= 1.0f)) {
      throw InvalidArgument(fmt::format("points[{}]", i), fmt::format("alpha must be in [0, 1], got {}", p.alpha));
    }
    if (p.color.r < 0.0f || p.color.g < 0.0f || p.color.b < 0.0f) {
      throw InvalidArgument(fmt::format("points[{}]", i), "colour components must not be negative");
    }
  }
  std::stable_sort(points_.begin(), points_.end(),
                   [](const TransferFunctionPoint& a, const TransferFunctionPoint& b) { return a.value < b.value; });
}

void TransferFunction::set_range(std::optional<vec2> range) {
  if (range && (!is_finite(range->x) || !is_finite(range->y) || !(range->x < range->y))) {
    throw InvalidArgument("range", fmt::format("an explicit range needs finite min < max, got [{}, {}]",
                                               range->x, range->y));
  }
  range_ = range;
}

vec2 TransferFunction::resolve_range(vec2 data_range) const {
  vec2 r = range_ ? *range_ : data_range;
  if (!(r.y > r.x)) r.y = r.x + 1.0f;
  return r;
}

void TransferFunction::set_unit_length(std::optional<float> unit_length) {
  if (unit_length && !(*unit_length > 0.0f && is_finite(*unit_length))) {
    throw InvalidArgument("unit_length", fmt::format("must be a positive length, got {}", *unit_length));
  }
  unit_length_ = unit_length;
}

void TransferFunction::set_density_scale(float scale) {
  if (!(scale >= 0.0f && is_finite(scale))) {
    throw InvalidArgument("density_scale", fmt::format("must be >= 0, got {}", scale));
  }
  density_scale_ = scale;
}

vec4 TransferFunction::evaluate(float x) const {
  const auto& p = points_;
  if (x <= p.front().value) return vec4(p.front().color, p.front().alpha);
  if (x >= p.back().value) return vec4(p.back().color, p.back().alpha);
  const auto upper = std::upper_bound(p.begin(), p.end(), x,
                                      [](float v, const TransferFunctionPoint& q) { return v < q.value; });
  const TransferFunctionPoint& b = *upper;
  const TransferFunctionPoint& a = *(upper - 1);
  const float w = b.value > a.value ? (x - a.value) / (b.value - a.value) : 1.0f;
  return glm::mix(vec4(a.color, a.alpha), vec4(b.color, b.alpha), w);
}

float TransferFunction::max_opacity(float lo, float hi) const {
  if (hi < lo) std::swap(lo, hi);
  float m = std::max(evaluate(lo).a, evaluate(hi).a);
  for (const TransferFunctionPoint& p : points_) {
    if (p.value > lo && p.value < hi) m = std::max(m, p.alpha);
  }
  return m;
}

TransferFunctionTable::TransferFunctionTable(const TransferFunction& tf, vec2 value_range, float unit_length,
                                             int size)
    : value_range_(value_range) {
  if (size < 2) throw InvalidArgument("size", "a transfer function table needs at least two entries");
  if (!(unit_length > 0.0f)) throw InvalidArgument("unit_length", "must be positive");
  entries_.resize(static_cast<std::size_t>(size));
  const float scale = tf.density_scale() / unit_length;
  for (int i = 0; i < size; ++i) {
    const vec4 c = tf.evaluate(float(i) / float(size - 1));
    const float alpha = std::min(c.a, TransferFunction::kMaxAlpha);
    entries_[static_cast<std::size_t>(i)] = vec4(vec3(c), -std::log1p(-alpha) * scale);
  }
  // Sparse table for constant-time range maxima of sigma_t.
  max_levels_.push_back({});
  for (const vec4& e : entries_) max_levels_[0].push_back(e.a);
  sigma_ = max_levels_[0];
  for (int k = 1; (1 << k) <= size; ++k) {
    const std::vector<float>& prev = max_levels_[static_cast<std::size_t>(k - 1)];
    std::vector<float> level(static_cast<std::size_t>(size - (1 << k) + 1));
    for (std::size_t i = 0; i < level.size(); ++i) level[i] = std::max(prev[i], prev[i + (1u << (k - 1))]);
    max_levels_.push_back(std::move(level));
  }
}

TransferFunctionView TransferFunctionTable::view() const {
  TransferFunctionView v;
  v.entries = entries_.data();
  v.sigma = sigma_.data();
  v.size = static_cast<int>(entries_.size());
  v.value_min = value_range_.x;
  const float width = value_range_.y - value_range_.x;
  v.index_scale = width > 0.0f ? float(v.size - 1) / width : 0.0f;
  return v;
}

float TransferFunctionTable::max_extinction(float lo, float hi) const {
  if (entries_.empty() || !(lo <= hi)) return 0.0f;  // empty or non-finite range: nothing to see
  const TransferFunctionView v = view();
  const float last = float(v.size - 1);
  const float x0 = std::clamp((lo - v.value_min) * v.index_scale, 0.0f, last);
  const float x1 = std::clamp((hi - v.value_min) * v.index_scale, 0.0f, last);
  const int i0 = static_cast<int>(std::floor(x0));
  const int i1 = static_cast<int>(std::ceil(x1));
  const int count = i1 - i0 + 1;
  const int k = std::bit_width(static_cast<unsigned>(count)) - 1;
  const auto& level = max_levels_[static_cast<std::size_t>(k)];
  return std::max(level[static_cast<std::size_t>(i0)], level[static_cast<std::size_t>(i1 - (1 << k) + 1)]);
}

}  // namespace penumbra

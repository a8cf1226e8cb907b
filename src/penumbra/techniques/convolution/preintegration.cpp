#include "penumbra/techniques/convolution/preintegration.h"

#include "penumbra/base/error.h"
#include "penumbra/base/memory_budget.h"
#include "penumbra/base/parallel.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <utility>

namespace penumbra {
namespace {

// Integral functions of the TF view's piecewise-linear sigma and colour * sigma
// at a position x in entry units (0..size-1), in value units:
//   S(x) = int sigma ds,   K(x) = int c sigma ds.
// Within an entry interval both factors are linear, so the closed forms below
// (a quadratic and a cubic in the fraction f) are exact.
class IntegralFunctions {
 public:
  explicit IntegralFunctions(const TransferFunctionView& tf)
      : tf_(tf), step_(1.0 / double(tf.index_scale)), s_(std::size_t(tf.size)), k_(std::size_t(tf.size)) {
    for (int e = 0; e + 1 < tf.size; ++e) {
      s_[std::size_t(e + 1)] = s_[std::size_t(e)] + piece_s(e, 1.0);
      k_[std::size_t(e + 1)] = k_[std::size_t(e)] + piece_k(e, 1.0);
    }
  }

  double s(double x) const {
    const auto [e, f] = split(x);
    return s_[std::size_t(e)] + piece_s(e, f);
  }
  glm::dvec3 k(double x) const {
    const auto [e, f] = split(x);
    return k_[std::size_t(e)] + piece_k(e, f);
  }

 private:
  std::pair<int, double> split(double x) const {
    x = std::clamp(x, 0.0, double(tf_.size - 1));
    const int e = std::min(int(x), tf_.size - 2);
    return {e, x - double(e)};
  }
  // int_0^f of sigma over entry interval e (fraction f in [0, 1]).
  double piece_s(int e, double f) const {
    const double s0 = tf_.entries[e].a, ds = double(tf_.entries[e + 1].a) - s0;
    return step_ * f * (s0 + 0.5 * f * ds);
  }
  glm::dvec3 piece_k(int e, double f) const {
    const double s0 = tf_.entries[e].a, ds = double(tf_.entries[e + 1].a) - s0;
    const glm::dvec3 c0(vec3(tf_.entries[e])), dc = glm::dvec3(vec3(tf_.entries[e + 1])) - c0;
    return step_ * f * (c0 * s0 + 0.5 * f * (c0 * ds + dc * s0) + (f * f / 3.0) * dc * ds);
  }

  TransferFunctionView tf_;
  double step_;  // value units per entry
  std::vector<double> s_;
  std::vector<glm::dvec3> k_;
};

void check_arguments(const TransferFunctionView& tf, float length, int size) {
  if (size < 2 || size > PreintegrationTable::kMaxSize)
    throw InvalidArgument("size", "a pre-integration table needs 2 to " +
                                      std::to_string(PreintegrationTable::kMaxSize) + " entries per axis, got " +
                                      std::to_string(size));
  if (!(length > 0.0f) || !std::isfinite(length))
    throw InvalidArgument("length", "the pre-integrated segment length must be positive and finite");
  if (tf.entries == nullptr || tf.size < 2)
    throw InvalidArgument("transfer_function", "pre-integration needs a transfer function table of 2 or more entries");
  if (!(tf.index_scale > 0.0f) || !std::isfinite(tf.index_scale))
    throw InvalidArgument("transfer_function", "pre-integration needs a transfer function with a value range");
}

}  // namespace

PreintegrationTable::PreintegrationTable(const TransferFunctionView& tf, float length, int size)
    : size_(size), length_(length), value_min_(tf.value_min) {
  check_arguments(tf, length, size);
  check_memory_budget("pre-integration table",
                      checked_product({std::uint64_t(size), std::uint64_t(size), sizeof(vec4)}));
  entries_.resize(std::size_t(size) * std::size_t(size));
  const int n = size;
  // Table value i sits at TF entry position x_i = i * entries_per_step.
  const double entries_per_step = double(tf.size - 1) / double(n - 1);
  const double value_step = entries_per_step / double(tf.index_scale);
  index_scale_ = float(1.0 / value_step);

  const IntegralFunctions integral(tf);
  const auto count = static_cast<std::size_t>(n);
  std::vector<double> s(count);
  std::vector<glm::dvec3> k(count);
  for (int i = 0; i < n; ++i) {
    s[std::size_t(i)] = integral.s(double(i) * entries_per_step);
    k[std::size_t(i)] = integral.k(double(i) * entries_per_step);
  }
  // Sub-segment m = [value m, value m + 1]: its integral of sigma and its
  // sigma-weighted mean colour (any colour where it has no extinction).
  std::vector<double> ds(count - 1);
  std::vector<glm::dvec3> mean_colour(count - 1);
  for (int m = 0; m + 1 < n; ++m) {
    ds[std::size_t(m)] = std::max(0.0, s[std::size_t(m + 1)] - s[std::size_t(m)]);
    mean_colour[std::size_t(m)] =
        ds[std::size_t(m)] > 0.0
            ? (k[std::size_t(m + 1)] - k[std::size_t(m)]) / ds[std::size_t(m)]
            : glm::dvec3(vec3(tf.lookup_finite(value_min_ + float((m + 0.5) * value_step))));
  }
  const double len = double(length);
  const auto value = [&](int i) { return value_min_ + float(double(i) * value_step); };

  // s_f == s_b: the single sample.
  for (int i = 0; i < n; ++i) {
    const vec4 c = tf.lookup_finite(value(i));
    entries_[std::size_t(i) * std::size_t(n + 1)] = vec4(vec3(c), float(-std::expm1(-len * double(c.a))));
  }

  parallel_for(1, n, [&](std::int64_t d_begin, std::int64_t d_end) {
    std::vector<double> transmit(count - 1), opacity(count - 1);
    for (int d = int(d_begin); d < int(d_end); ++d) {
      // A sub-segment of a segment spanning d table steps has world length
      // L / d and mean extinction ds_m / value_step.
      const double scale = len / (double(d) * value_step);
      for (int m = 0; m + 1 < n; ++m) {
        const double tau = scale * ds[std::size_t(m)];
        transmit[std::size_t(m)] = std::exp(-tau);
        opacity[std::size_t(m)] = -std::expm1(-tau);
      }
      for (int i = 0; i + d < n; ++i) {
        const int j = i + d;
        const float alpha = float(-std::expm1(-scale * std::max(0.0, s[std::size_t(j)] - s[std::size_t(i)])));
        const vec3 fallback(tf.lookup_finite(0.5f * (value(i) + value(j))));
        for (int direction = 0; direction < 2; ++direction) {
          // Front to back over the sub-segments: i -> j, then j -> i.
          double transmittance = 1.0, accumulated = 0.0;
          glm::dvec3 colour(0.0);
          for (int step = 0; step < d && transmittance > 0.0; ++step) {
            const std::size_t m = std::size_t(direction == 0 ? i + step : j - 1 - step);
            const double w = transmittance * opacity[m];
            colour += w * mean_colour[m];
            accumulated += w;
            transmittance *= transmit[m];
          }
          const vec3 c = accumulated > 0.0 ? vec3(colour / accumulated) : fallback;
          const int front = direction == 0 ? i : j, back = direction == 0 ? j : i;
          entries_[std::size_t(front) * std::size_t(n) + std::size_t(back)] = vec4(c, alpha);
        }
      }
    }
  });
}

PreintegrationView PreintegrationTable::view() const {
  PreintegrationView v;
  v.entries = entries_.data();
  v.size = size_;
  v.value_min = value_min_;
  v.index_scale = index_scale_;
  return v;
}

bool PreintegrationCache::update(const TransferFunctionView& tf, float length, int size) {
  check_arguments(tf, length, size);
  const bool same_tf = tf_entries_.size() == std::size_t(tf.size) && tf_value_min_ == tf.value_min &&
                       tf_index_scale_ == tf.index_scale &&
                       std::memcmp(tf_entries_.data(), tf.entries, tf_entries_.size() * sizeof(vec4)) == 0;
  if (same_tf && !table_.empty() && table_.length() == length && table_.size() == size) return false;
  table_ = PreintegrationTable(tf, length, size);
  tf_entries_.assign(tf.entries, tf.entries + tf.size);
  tf_value_min_ = tf.value_min;
  tf_index_scale_ = tf.index_scale;
  return true;
}

}  // namespace penumbra

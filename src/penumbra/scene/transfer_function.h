#pragma once
// Transfer function: scalar value -> (linear rgb, alpha), piecewise linear over
// control points whose values are normalised to a range ("data" = the volume's
// min..max over all frames, or explicit). alpha is the opacity of a slab of the
// reference length unit_length; the extinction coefficient is
//   sigma_t = -ln(1 - alpha) / unit_length * density_scale      (DESIGN.md 1)
// with alpha clamped to kMaxAlpha. TransferFunctionTable bakes it for kernels.
#include "penumbra/base/math.h"

#include <optional>
#include <vector>

namespace penumbra {

struct TransferFunctionPoint {
  float value = 0.0f;  // normalised to the TF's range: 0 = range min, 1 = range max
  vec3 color{1.0f};    // linear rgb
  float alpha = 0.0f;  // opacity of a slab of unit_length
};

class TransferFunction {
 public:
  static constexpr float kMaxAlpha = 1.0f - 1e-6f;

  // A grey ramp from transparent black at 0 to opaque white at 1.
  TransferFunction();
  // Sorts the points by value; throws InvalidArgument for no points, values or
  // colours that are not finite, or alpha outside [0, 1].
  explicit TransferFunction(std::vector<TransferFunctionPoint> points);

  const std::vector<TransferFunctionPoint>& points() const { return points_; }

  // Explicit value range in data units, or nullopt for "data".
  const std::optional<vec2>& range() const { return range_; }
  void set_range(std::optional<vec2> range);
  // The range in data units given the volume's value range; a range of zero
  // width is widened to [min, min + 1] so a constant volume maps to 0.
  vec2 resolve_range(vec2 data_range) const;

  // Reference length in world units; nullopt = the volume's smallest spacing.
  const std::optional<float>& unit_length() const { return unit_length_; }
  void set_unit_length(std::optional<float> unit_length);

  float density_scale() const { return density_scale_; }
  void set_density_scale(float scale);

  // (rgb, alpha) at a normalised value; clamps to the end points outside them.
  vec4 evaluate(float normalized) const;
  // Largest alpha over the normalised interval [lo, hi] (exact: the function is
  // piecewise linear, so the maximum is at an end or a control point).
  float max_opacity(float lo, float hi) const;

 private:
  std::vector<TransferFunctionPoint> points_;
  std::optional<vec2> range_;
  std::optional<float> unit_length_;
  float density_scale_ = 1.0f;
};

// The plain view kernels use: entries of (r, g, b, sigma_t) sampled uniformly
// over the value range in data units, linearly interpolated. The lookups are
// written over a lane type (base/lanes.h); locate() once, then sigma_t() and
// color() of the same place, so a kernel can skip the colour where no lane
// has extinction.
struct TransferFunctionView {
  const vec4* entries = nullptr;
  const float* sigma = nullptr;  // entries[i].a on their own: 4x denser for lookups that need only extinction
  int size = 0;
  float value_min = 0.0f;
  float index_scale = 0.0f;  // (size - 1) / (value_max - value_min)

  template <class L> struct Place {
    typename L::Index entry;    // i: between entries i and i + 1
    typename L::Float fraction;  // toward entry i + 1
  };

  // Where a finite data value falls in the table (values outside the range
  // take the end entries).
  template <class L> PENUMBRA_HD PENUMBRA_FORCE_INLINE Place<L> locate(typename L::Float value) const {
    using F = typename L::Float;
    using I = typename L::Int;
    F x = (value - value_min) * index_scale;
    x = select(x < 0.0f, F(0.0f), x);
    const float last = float(size - 1);
    x = select(x > last, F(last), x);
    I i = to_int_nonnegative(x);
    i = select(i > I(size - 2), I(size - 2), i);
    return Place<L>{typename L::Index(i), x - to_float(i)};
  }
  template <class L> PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Float sigma_t(const Place<L>& at) const {
    const typename L::Float a = gather(sigma, at.entry), b = gather(sigma + 1, at.entry);
    return a + at.fraction * (b - a);
  }
  template <class L> PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Vec3 color(const Place<L>& at) const {
    using F = typename L::Float;
    const float* e = &entries[0].x;
    const typename L::Index first = at.entry * 4;
    const F r0 = gather(e + 0, first), r1 = gather(e + 4, first);
    const F g0 = gather(e + 1, first), g1 = gather(e + 5, first);
    const F b0 = gather(e + 2, first), b1 = gather(e + 6, first);
    return typename L::Vec3(r0 + at.fraction * (r1 - r0), g0 + at.fraction * (g1 - g0), b0 + at.fraction * (b1 - b0));
  }

  // (rgb, sigma_t per world unit) for a data value. NaN and +-inf are
  // transparent; values outside the range take the end entries.
  PENUMBRA_HD PENUMBRA_FORCE_INLINE vec4 lookup(float value) const {
    if (!is_finite(value)) return vec4(0.0f);
    return lookup_finite(value);
  }

  // The same for a value known to be finite (integer voxel types).
  PENUMBRA_HD PENUMBRA_FORCE_INLINE vec4 lookup_finite(float value) const {
    const Place<ScalarLanes> at = locate<ScalarLanes>(value);
    return vec4(color<ScalarLanes>(at), sigma_t<ScalarLanes>(at));
  }
};

class TransferFunctionTable {
 public:
  static constexpr int kDefaultSize = 4096;

  TransferFunctionTable() = default;
  // noexcept moves, so that a std::vector of tables moves them when it grows
  // (the implicit move is not noexcept: glm's copy constructors under
  // GLM_FORCE_CTOR_INIT are not).
  TransferFunctionTable(TransferFunctionTable&&) noexcept = default;
  TransferFunctionTable& operator=(TransferFunctionTable&&) noexcept = default;
  TransferFunctionTable(const TransferFunctionTable&) = default;
  TransferFunctionTable& operator=(const TransferFunctionTable&) = default;
  // value_range in data units (already resolved); unit_length in world units.
  TransferFunctionTable(const TransferFunction& tf, vec2 value_range, float unit_length,
                        int size = kDefaultSize);

  TransferFunctionView view() const;
  vec2 value_range() const { return value_range_; }

  // Largest sigma_t a lookup can return for any value in [lo, hi] (data units):
  // the maximum over the entries that interpolation between them can reach.
  // Constant time (sparse table of maxima).
  float max_extinction(float lo, float hi) const;

 private:
  std::vector<vec4> entries_;
  std::vector<float> sigma_;  // entries_[i].a
  vec2 value_range_{0.0f, 1.0f};
  std::vector<std::vector<float>> max_levels_;  // max_levels_[k][i] = max sigma over [i, i + 2^k)
};

}  // namespace penumbra

#include "penumbra/techniques/convolution/slab_kernel.h"

#include "penumbra/base/error.h"
#include "penumbra/techniques/convolution/ellipse_tables.h"
#include "penumbra/techniques/convolution/gaussian_light.h"

#include <algorithm>
#include <cmath>

namespace penumbra {
namespace {

constexpr double kTwoPi = 6.283185307179586;
constexpr int kArcSteps = 1024;

// N points in the unit disk at least r apart (dart throwing with a fixed
// seed), centred and scaled to variance 1 per axis under random rotation.
std::vector<vec2> poisson_pattern(int n) {
  Pcg32 rng(0x5eedULL);
  float r = 1.6f / std::sqrt(float(n));
  std::vector<vec2> points;
  while (int(points.size()) < n) {
    points.clear();
    for (int attempt = 0; attempt < 20000 && int(points.size()) < n; ++attempt) {
      const vec2 p(2.0f * rng.next_float() - 1.0f, 2.0f * rng.next_float() - 1.0f);
      if (glm::dot(p, p) > 1.0f) continue;
      bool far = true;
      for (const vec2& q : points) far = far && glm::distance(p, q) >= r;
      if (far) points.push_back(p);
    }
    r *= 0.9f;
  }
  vec2 mean(0.0f);
  for (const vec2& p : points) mean += p / float(n);
  double r2 = 0.0;
  for (vec2& p : points) {
    p -= mean;
    r2 += double(glm::dot(p, p)) / double(n);
  }
  // Under a uniform rotation E[x^2] = E[|p|^2] / 2.
  const float scale = r2 > 0.0 ? float(std::sqrt(2.0 / r2)) : 0.0f;
  for (vec2& p : points) p *= scale;
  return points;
}

}  // namespace

SlabKernelType parse_slab_kernel(const std::string& name) {
  if (name == "gaussian") return SlabKernelType::Gaussian;
  if (name == "poisson") return SlabKernelType::Poisson;
  if (name == "ellipse") return SlabKernelType::Ellipse;
  throw InvalidArgument("kernel", "must be gaussian, poisson or ellipse");
}

SlabKernelBuilder::SlabKernelBuilder(SlabKernelType type, int samples, vec2 mean, const glm::mat2& covariance,
                                     std::uint64_t seed)
    : type_(type), mean_(mean), seed_(seed) {
  const PrincipalAxes axes = principal_axes(covariance);
  angle_ = axes.angle;
  const vec2 ex(std::cos(angle_), std::sin(angle_)), ey(-ex.y, ex.x);
  axis_x_ = std::sqrt(axes.var_x) * ex;
  axis_y_ = std::sqrt(axes.var_y) * ey;
  const bool point = axes.var_x <= 0.0f && axes.var_y <= 0.0f;
  switch (type) {
    case SlabKernelType::Gaussian: {
      int m = samples > 0 ? samples : 19;
      if (m % 2 == 0) ++m;
      if (point) m = 1;
      std::vector<double> pos(std::size_t(m), 0.0), w(std::size_t(m), 1.0);
      double sum = 0.0, var = 0.0;
      for (int i = 0; i < m; ++i) {
        pos[std::size_t(i)] = m > 1 ? 3.0 * (2.0 * i / double(m - 1) - 1.0) : 0.0;
        w[std::size_t(i)] = std::exp(-0.5 * pos[std::size_t(i)] * pos[std::size_t(i)]);
        sum += w[std::size_t(i)];
      }
      for (int i = 0; i < m; ++i) {
        w[std::size_t(i)] /= sum;
        var += w[std::size_t(i)] * pos[std::size_t(i)] * pos[std::size_t(i)];
      }
      const double rescale = var > 0.0 ? 1.0 / std::sqrt(var) : 0.0;
      for (int i = 0; i < m; ++i) {
        for (int j = 0; j < m; ++j) {
          taps_.push_back(mean_ + float(pos[std::size_t(i)] * rescale) * axis_x_ +
                          float(pos[std::size_t(j)] * rescale) * axis_y_);
          weights_.push_back(float(w[std::size_t(i)] * w[std::size_t(j)]));
        }
      }
      break;
    }
    case SlabKernelType::Poisson: {
      const int n = point ? 1 : std::max(samples > 0 ? samples : 8, 2);
      unit_ = point ? std::vector<vec2>{vec2(0.0f)} : poisson_pattern(n);
      weights_.assign(std::size_t(n), 1.0f / float(n));
      break;
    }
    case SlabKernelType::Ellipse: {
      const int n = point ? 1 : std::max(samples > 0 ? samples : 2, 2);
      radii_ = EllipseTables::instance().radii(axes.var_x, axes.var_y);
      arc_.assign(kArcSteps + 1, 0.0);
      for (int i = 1; i <= kArcSteps; ++i) {
        const double th = kTwoPi * (i - 0.5) / kArcSteps;
        arc_[std::size_t(i)] = arc_[std::size_t(i) - 1] +
                               std::hypot(radii_.x * std::sin(th), radii_.y * std::cos(th)) * kTwoPi / kArcSteps;
      }
      weights_.assign(std::size_t(n), 1.0f / float(n));
      taps_.assign(std::size_t(n), mean_);
      break;
    }
  }
}

SlabKernel SlabKernelBuilder::for_slab(int slab) {
  SlabKernel k;
  k.weights = weights_.data();
  k.count = int(weights_.size());
  k.mean = mean_;
  k.seed = mix_bits(seed_ * 0x9e3779b97f4a7c15ULL + std::uint64_t(slab));
  if (type_ == SlabKernelType::Poisson) {
    k.taps = unit_.data();
    k.rotate_per_pixel = k.count > 1;
    k.axis_x = axis_x_;
    k.axis_y = axis_y_;
    if (!k.rotate_per_pixel) {
      taps_.assign(1, mean_);
      k.taps = taps_.data();
    }
    return k;
  }
  if (type_ == SlabKernelType::Ellipse && k.count > 1) {
    // Equidistant arc lengths from a random start; invert the cumulative table.
    const double total = arc_.back();
    const double start = double(k.seed >> 11) * (1.0 / 9007199254740992.0);
    const vec2 ex(std::cos(angle_), std::sin(angle_)), ey(-ex.y, ex.x);
    for (int j = 0; j < k.count; ++j) {
      const double s = std::fmod(start + double(j) / k.count, 1.0) * total;
      const std::size_t i = std::size_t(std::upper_bound(arc_.begin(), arc_.end(), s) - arc_.begin());
      const std::size_t hi = std::clamp<std::size_t>(i, 1, kArcSteps);
      const double seg = arc_[hi] - arc_[hi - 1];
      const double f = seg > 0.0 ? (s - arc_[hi - 1]) / seg : 0.0;
      const double th = kTwoPi * (double(hi - 1) + f) / kArcSteps;
      taps_[std::size_t(j)] = mean_ + float(radii_.x * std::cos(th)) * ex + float(radii_.y * std::sin(th)) * ey;
    }
  }
  k.taps = taps_.data();
  return k;
}

}  // namespace penumbra

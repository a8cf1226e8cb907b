#include "penumbra/techniques/convolution/ellipse_tables.h"

#include <algorithm>
#include <cmath>

namespace penumbra {
namespace {

// Arithmetic-geometric mean iteration shared by K and E (Abramowitz & Stegun
// 17.6): K = pi / (2 a_inf); E = K (1 - sum_n 2^(n-1) c_n^2), c_0 = k.
void agm(double k, double& big_k, double& big_e) {
  double a = 1.0, b = std::sqrt(std::max(0.0, 1.0 - k * k)), c = k;
  double sum = 0.5 * c * c, power = 0.5;
  for (int i = 0; i < 40 && std::abs(c) > 1e-17; ++i) {
    c = 0.5 * (a - b);
    const double an = 0.5 * (a + b);
    b = std::sqrt(a * b);
    a = an;
    power *= 2.0;
    sum += power * c * c;
  }
  big_k = 3.14159265358979323846 / (2.0 * a);
  big_e = big_k * (1.0 - sum);
}

// V_y / V_x of the unit ellipse (1 - t, t).
double unit_ratio(double t) {
  const glm::dvec2 v = ellipse_variances(1.0 - t, t);
  return v.x > 0.0 ? v.y / v.x : kInfinity;
}

}  // namespace

double elliptic_k(double k) {
  double big_k, big_e;
  agm(k, big_k, big_e);
  return big_k;
}

double elliptic_e(double k) {
  double big_k, big_e;
  agm(k, big_k, big_e);
  return big_e;
}

double ellipse_var_x(double b) {
  b = std::clamp(b, 0.0, 1.0);
  const double b2 = b * b;
  // Near the circle the expression is 0/0; its limit there is 1/2.
  if (b2 > 1.0 - 1e-9) return 0.5;
  if (b == 0.0) return 1.0 / 3.0;
  const double k = std::sqrt(1.0 - b2);
  return (2.0 * b2 - 1.0 - b2 * elliptic_k(k) / elliptic_e(k)) / (-3.0 + 3.0 * b2);
}

glm::dvec2 ellipse_variances(double a, double b) {
  if (a <= 0.0 && b <= 0.0) return glm::dvec2(0.0);
  if (b <= a) {
    const double v = ellipse_var_x(b / a);
    return glm::dvec2(a * a * v, b * b * (1.0 - v));
  }
  const double v = ellipse_var_x(a / b);
  return glm::dvec2(a * a * (1.0 - v), b * b * v);
}

EllipseTables::EllipseTables(int size) {
  size = std::max(size, 16);
  var_x_.resize(std::size_t(size) + 1);
  for (int i = 0; i <= size; ++i) {
    const double t = double(i) / double(size);
    var_x_[std::size_t(i)] = ellipse_variances(1.0 - t, t).x;
  }
  // For ratio r = s^2 <= 1 the answer lies in t <= 1/2 and behaves like
  // sqrt(r / 2) near 0, hence the table over s = sqrt(r) (linear there).
  t_of_root_.resize(std::size_t(size) + 1);
  for (int i = 0; i <= size; ++i) {
    const double s = double(i) / double(size);
    const double target = s * s;
    double lo = 0.0, hi = 0.5;
    for (int it = 0; it < 60; ++it) {
      const double mid = 0.5 * (lo + hi);
      (unit_ratio(mid) < target ? lo : hi) = mid;
    }
    t_of_root_[std::size_t(i)] = 0.5 * (lo + hi);
  }
}

double EllipseTables::ab_to_var_x(double t) const {
  const double n = double(var_x_.size() - 1);
  const double x = std::clamp(t, 0.0, 1.0) * n;
  const std::size_t i = std::min(std::size_t(x), var_x_.size() - 2);
  const double f = x - double(i);
  return var_x_[i] * (1.0 - f) + var_x_[i + 1] * f;
}

double EllipseTables::ratio_to_ab(double ratio) const {
  if (!(ratio >= 0.0)) return 0.0;
  if (ratio > 1.0) return 1.0 - ratio_to_ab(1.0 / ratio);  // mirror: swap the axes
  const double n = double(t_of_root_.size() - 1);
  const double x = std::sqrt(ratio) * n;
  const std::size_t i = std::min(std::size_t(x), t_of_root_.size() - 2);
  const double f = x - double(i);
  return t_of_root_[i] * (1.0 - f) + t_of_root_[i + 1] * f;
}

glm::dvec2 EllipseTables::radii(double var_x, double var_y) const {
  var_x = std::max(var_x, 0.0);
  var_y = std::max(var_y, 0.0);
  if (var_x <= 0.0 && var_y <= 0.0) return glm::dvec2(0.0);
  const double t = var_x > 0.0 ? ratio_to_ab(var_y / var_x) : 1.0;
  // Scale by the larger axis: its unit variance is the better conditioned.
  const double scale = var_x >= var_y ? var_x / ab_to_var_x(t) : var_y / ab_to_var_x(1.0 - t);
  const double root = std::sqrt(scale);
  return glm::dvec2((1.0 - t) * root, t * root);
}

const EllipseTables& EllipseTables::instance() {
  static const EllipseTables tables;
  return tables;
}

}  // namespace penumbra

#pragma once
// Elliptic kernel shape for a requested variance (Patel et al. 2013, section
// 3.4 and appendix A.7). N points equidistant in arc length on an ellipse with
// radii (a, b), with a uniformly random offset along the circumference, are
// distributed with the arc-length density of the ellipse; its x and y
// variances have no closed form, so two tables are built once:
//   abToVarx(t):   x variance V_x of the "unit" ellipse a = 1 - t, b = t,
//   ratioToab(r):  the t whose unit ellipse has V_y / V_x = r (numerical
//                  inversion of V_y / V_x, which rises monotonically in t).
// var_x(b), the x variance of the ellipse with radii (1, b <= 1), is the
// appendix's expression in the complete elliptic integrals K and E of modulus
// sqrt(1 - b^2); the y variance of that ellipse is b^2 (1 - var_x(b)) because
// the arc-length means of cos^2 and sin^2 add up to one.
#include "penumbra/base/math.h"

#include <vector>

namespace penumbra {

// Complete elliptic integrals of the first and second kind, modulus k in
// [0, 1) (arithmetic-geometric mean; double precision).
double elliptic_k(double k);
double elliptic_e(double k);

// Variance of the x projection of the arc-length density of the ellipse with
// radii (1, b), b in [0, 1] (1/3 for the segment, 1/2 for the circle).
double ellipse_var_x(double b);

// (x, y) variances of the arc-length density of the ellipse with radii (a, b).
glm::dvec2 ellipse_variances(double a, double b);

class EllipseTables {
 public:
  explicit EllipseTables(int size = 1024);

  double ab_to_var_x(double t) const;    // table lookup, t in [0, 1]
  double ratio_to_ab(double ratio) const;  // table lookup, ratio in [0, inf]

  // Radii (a along x, b along y) of the ellipse whose arc-length density has
  // variances (var_x, var_y); (0, 0) for a zero request.
  glm::dvec2 radii(double var_x, double var_y) const;

  static const EllipseTables& instance();

 private:
  std::vector<double> var_x_;     // over t in [0, 1]
  std::vector<double> t_of_root_; // over s = sqrt(ratio) in [0, 1]; t in [0, 1/2]
};

}  // namespace penumbra

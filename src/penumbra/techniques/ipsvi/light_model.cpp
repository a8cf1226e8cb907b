#include "penumbra/techniques/ipsvi/light_model.h"

#include <algorithm>
#include <cmath>

namespace penumbra {
namespace {

// Primitive of the 4 pi-normalised Henyey-Greenstein phase function in
// u = cos(angle): (1 - g^2) / g (1 + g^2 - 2 g u)^-1/2.
double hg_primitive(double g, double u) { return (1.0 - g * g) / g / std::sqrt(1.0 + g * g - 2.0 * g * u); }

double hg(double g, double u) { return (1.0 - g * g) / std::pow(1.0 + g * g - 2.0 * g * u, 1.5); }

}  // namespace

// The integral over the cone (axis a, half-angle theta) of p(w . v), v the
// view direction at angle alpha from a, in polar coordinates around v: the
// directions at angle beta from v form a circle, of which the fraction
// f(beta) lies in the cone, so the integral is 2 pi times that of
// p(u) f(u) over u = cos(beta) in [-1, 1]. A point of that circle at
// azimuth phi has cos(angle to a) = cos(alpha) u + sin(alpha) sin(beta)
// cos(phi), so f = acos(clamp(x)) / pi with x = (cos(theta) - cos(alpha) u) /
// (sin(alpha) sin(beta)). f is smooth but at u = cos(theta + alpha) and
// cos(|theta - alpha|); between those the integral is taken as f at the
// midpoints of 128 pieces times p's exact integral over each piece, which
// holds the phase function's peak however sharp it is.
ConePhase make_cone_phase(float g, float cone_angle_deg) {
  ConePhase out;
  const double theta = double(glm::radians(cone_angle_deg));
  const double gg = double(g);
  const double cos_theta = std::cos(theta);
  for (int i = 0; i <= ConePhase::kEntries; ++i) {
    out.ratio[i] = 1.0f;
    if (!(theta > 0.0) || std::abs(gg) < 1e-6) continue;
    const double mu = std::clamp(-1.0 + 2.0 * double(i) / double(ConePhase::kEntries), -1.0, 1.0);
    const double alpha = std::acos(mu), sin_alpha = std::sin(alpha);
    auto fraction = [&](double u) {
      const double s = sin_alpha * std::sqrt(std::max(0.0, 1.0 - u * u));
      if (s < 1e-12) return mu * u >= cos_theta ? 1.0 : 0.0;
      return std::acos(std::clamp((cos_theta - mu * u) / s, -1.0, 1.0)) / double(kPi);
    };
    const double bounds[4] = {-1.0, theta + alpha < double(kPi) ? std::cos(theta + alpha) : -1.0,
                              std::cos(std::abs(theta - alpha)), 1.0};
    double integral = 0.0;
    for (int segment = 0; segment < 3; ++segment) {
      const double lo = bounds[segment], hi = bounds[segment + 1];
      if (!(hi > lo)) continue;
      constexpr int kPieces = 128;
      for (int k = 0; k < kPieces; ++k) {
        const double u0 = lo + (hi - lo) * double(k) / kPieces, u1 = lo + (hi - lo) * double(k + 1) / kPieces;
        integral += fraction(0.5 * (u0 + u1)) * (hg_primitive(gg, u1) - hg_primitive(gg, u0));
      }
    }
    const double mean = integral / (1.0 - cos_theta);  // the solid angle's 2 pi cancels
    out.ratio[i] = float(mean / hg(gg, mu));
  }
  return out;
}

}  // namespace penumbra

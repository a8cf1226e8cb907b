#include "penumbra/analysis/color_difference.h"

#include <cmath>

namespace penumbra {
namespace {

constexpr double kDegrees = 180.0 / 3.14159265358979323846;
constexpr double kRadians = 3.14159265358979323846 / 180.0;

double pow7(double x) {
  const double x2 = x * x;
  return x2 * x2 * x2 * x;
}

// Hue angle in degrees in [0, 360); Sharma et al. define it as 0 for a
// neutral colour, where atan2 alone would be arbitrary.
double hue_degrees(double b, double a_prime) {
  if (b == 0.0 && a_prime == 0.0) return 0.0;
  const double h = std::atan2(b, a_prime) * kDegrees;
  return h < 0.0 ? h + 360.0 : h;
}

}  // namespace

double delta_e_76(const Lab& first, const Lab& second) {
  const double dl = first.l - second.l;
  const double da = first.a - second.a;
  const double db = first.b - second.b;
  return std::sqrt(dl * dl + da * da + db * db);
}

double delta_e_2000(const Lab& first, const Lab& second) {
  constexpr double k25pow7 = 6103515625.0;  // 25^7

  // Equations 2-7: stretch a* near the neutral axis, where CIELAB
  // understates chroma differences.
  const double c1 = std::hypot(first.a, first.b);
  const double c2 = std::hypot(second.a, second.b);
  const double mean_c7 = pow7(0.5 * (c1 + c2));
  const double g = 0.5 * (1.0 - std::sqrt(mean_c7 / (mean_c7 + k25pow7)));
  const double a1 = (1.0 + g) * first.a;
  const double a2 = (1.0 + g) * second.a;
  const double chroma1 = std::hypot(a1, first.b);
  const double chroma2 = std::hypot(a2, second.b);
  const double hue1 = hue_degrees(first.b, a1);
  const double hue2 = hue_degrees(second.b, a2);

  // Equations 8-12: differences, with the hue difference taken the short way
  // round the circle and zero when either colour is neutral.
  const double delta_l = second.l - first.l;
  const double delta_c = chroma2 - chroma1;
  const double chroma_product = chroma1 * chroma2;
  double delta_hue = 0.0;
  if (chroma_product != 0.0) {
    delta_hue = hue2 - hue1;
    if (delta_hue > 180.0) {
      delta_hue -= 360.0;
    } else if (delta_hue < -180.0) {
      delta_hue += 360.0;
    }
  }
  const double delta_h = 2.0 * std::sqrt(chroma_product) * std::sin(0.5 * delta_hue * kRadians);

  // Equations 13-16: means, with the mean hue also taken the short way round
  // (and the plain sum when one colour is neutral, as the paper specifies).
  const double mean_l = 0.5 * (first.l + second.l);
  const double mean_chroma = 0.5 * (chroma1 + chroma2);
  double mean_hue = hue1 + hue2;
  if (chroma_product != 0.0) {
    if (std::abs(hue1 - hue2) <= 180.0) {
      mean_hue *= 0.5;
    } else if (mean_hue < 360.0) {
      mean_hue = 0.5 * (mean_hue + 360.0);
    } else {
      mean_hue = 0.5 * (mean_hue - 360.0);
    }
  }

  // Equations 15-21: weighting functions and the blue-region rotation term.
  const double t = 1.0 - 0.17 * std::cos((mean_hue - 30.0) * kRadians) + 0.24 * std::cos(2.0 * mean_hue * kRadians) +
                   0.32 * std::cos((3.0 * mean_hue + 6.0) * kRadians) -
                   0.20 * std::cos((4.0 * mean_hue - 63.0) * kRadians);
  const double hue_offset = (mean_hue - 275.0) / 25.0;
  const double delta_theta = 30.0 * std::exp(-hue_offset * hue_offset);
  const double mean_chroma7 = pow7(mean_chroma);
  const double r_c = 2.0 * std::sqrt(mean_chroma7 / (mean_chroma7 + k25pow7));
  const double l50 = (mean_l - 50.0) * (mean_l - 50.0);
  const double s_l = 1.0 + 0.015 * l50 / std::sqrt(20.0 + l50);
  const double s_c = 1.0 + 0.045 * mean_chroma;
  const double s_h = 1.0 + 0.015 * mean_chroma * t;
  const double r_t = -std::sin(2.0 * delta_theta * kRadians) * r_c;

  // Equation 22.
  const double term_l = delta_l / s_l;
  const double term_c = delta_c / s_c;
  const double term_h = delta_h / s_h;
  return std::sqrt(term_l * term_l + term_c * term_c + term_h * term_h + r_t * term_c * term_h);
}

}  // namespace penumbra

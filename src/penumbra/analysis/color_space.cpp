#include "penumbra/analysis/color_space.h"

#include <cmath>

namespace penumbra {
namespace {

// IEC 61966-2-1:1999, equation (F.7): the published four-decimal matrix.
constexpr double kSrgbToXyz[3][3] = {
    {0.4124, 0.3576, 0.1805},
    {0.2126, 0.7152, 0.0722},
    {0.0193, 0.1192, 0.9505},
};

// D65 as the matrix sees it (its row sums). The CIE value derived from the
// chromaticity (0.3127, 0.3290) is (0.95047, 1, 1.08883); the difference is
// below 2e-4 relative, but using the row sums keeps greys exactly neutral.
constexpr dvec3 kWhite{kSrgbToXyz[0][0] + kSrgbToXyz[0][1] + kSrgbToXyz[0][2],
                       kSrgbToXyz[1][0] + kSrgbToXyz[1][1] + kSrgbToXyz[1][2],
                       kSrgbToXyz[2][0] + kSrgbToXyz[2][1] + kSrgbToXyz[2][2]};

// CIE 15:2004 L*a*b* companding: a cube root above (6/29)^3 and a straight
// line below it, so that the curve has finite slope at black.
double lab_companding(double t) {
  constexpr double delta = 6.0 / 29.0;
  if (t > delta * delta * delta) return std::cbrt(t);
  return t / (3.0 * delta * delta) + 4.0 / 29.0;
}

}  // namespace

float srgb_encode(float linear) {
  const float c = clamp01(linear);
  return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

float srgb_decode(float encoded) {
  const float c = clamp01(encoded);
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

vec3 srgb_encode(vec3 linear) { return {srgb_encode(linear.r), srgb_encode(linear.g), srgb_encode(linear.b)}; }

vec3 srgb_decode(vec3 encoded) { return {srgb_decode(encoded.r), srgb_decode(encoded.g), srgb_decode(encoded.b)}; }

dvec3 srgb_linear_to_xyz(vec3 linear_rgb) {
  const dvec3 c(linear_rgb);
  dvec3 xyz;
  for (int row = 0; row < 3; ++row) {
    xyz[row] = kSrgbToXyz[row][0] * c.r + kSrgbToXyz[row][1] * c.g + kSrgbToXyz[row][2] * c.b;
  }
  return xyz;
}

Lab xyz_to_lab(dvec3 xyz) {
  const double fx = lab_companding(xyz.x / kWhite.x);
  const double fy = lab_companding(xyz.y / kWhite.y);
  const double fz = lab_companding(xyz.z / kWhite.z);
  return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

Lab srgb_linear_to_lab(vec3 linear_rgb) { return xyz_to_lab(srgb_linear_to_xyz(linear_rgb)); }

}  // namespace penumbra

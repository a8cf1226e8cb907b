#pragma once
// sRGB transfer function and the linear sRGB -> CIE XYZ -> CIE L*a*b* chain
// used by the perceptual metrics. Lab is computed in double because CIEDE2000
// is evaluated near hue discontinuities where float rounding shows.
#include "penumbra/base/math.h"

namespace penumbra {

// CIE 1976 L*a*b* relative to the D65 white of the sRGB matrix below.
struct Lab {
  double l = 0.0;  // L*, 0 (black) .. 100 (white)
  double a = 0.0;  // a*, green (-) .. red (+)
  double b = 0.0;  // b*, blue (-) .. yellow (+)
};

// IEC 61966-2-1 transfer function, for values in [0, 1] (values outside are
// clamped first).
float srgb_encode(float linear);
float srgb_decode(float encoded);
vec3 srgb_encode(vec3 linear);
vec3 srgb_decode(vec3 encoded);

// Linear sRGB -> CIE XYZ (Y of white = 1) with the IEC 61966-2-1 matrix.
dvec3 srgb_linear_to_xyz(vec3 linear_rgb);

// CIE XYZ -> L*a*b* relative to the sRGB white (the matrix's image of
// rgb (1, 1, 1)), so that every neutral grey has a* = b* = 0 exactly.
Lab xyz_to_lab(dvec3 xyz);

// Linear sRGB -> L*a*b*. Takes the colour as given: callers that may hold
// out-of-gamut or HDR values clamp first (the image metrics clamp to [0, 1]).
Lab srgb_linear_to_lab(vec3 linear_rgb);

}  // namespace penumbra

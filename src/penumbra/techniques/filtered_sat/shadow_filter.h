#pragma once
// The low-pass filter over the patch facing the light (Ament et al. 2014,
// eq. 4): a square of half-width S in the plane orthogonal to the light,
// split into taps x taps sub-patches with separable weights. The box kernel
// (eq. 11) is one sub-patch of weight 1; the Gaussian (section 4.3, eq. 25)
// is 8 x 8 sub-patches over +-3 sigma, each weighted by the Gaussian's mass
// over it.
//
// "Comparable width": a box of width w and the Gaussian with the same
// variance w^2 / 12 (sigma = w / sqrt(12), slightly less once the taps are
// accounted for, see make_shadow_filter), so both blur equally in the
// second-moment sense and agree at low frequencies (1 - (2 pi f sigma)^2 / 2
// + ...).
#include "penumbra/base/math.h"
#include "penumbra/base/ray.h"
#include "penumbra/scene/light.h"

namespace penumbra {

enum class FilterKernel { Box, Gaussian };

struct ShadowFilter {
  static constexpr int kMaxTaps = 8;
  float half_width = 0.5f;  // S, world units
  int taps = 1;             // sub-patches per axis
  float weights[kMaxTaps] = {1.0f};  // per sub-patch along one axis, summing to 1
  float density_scale = 1.0f;        // multiplies the filtered optical depth
  // How far toward the light the filtered volume starts, world units (0:
  // at the sample, the paper's cuboid of eq. 10). A patch of full width at
  // the sample reaches into the material of the surface the sample lies on;
  // starting it farther leaves that material out (the self-shadowing
  // mitigation of issue 22).
  float offset = 0.0f;
};

// The filter for a box width (or, for the Gaussian, the box width of the same
// variance) in world units.
// `offset`: in units of the filter's half-width (the box's half-width, or
// for the Gaussian that of its box of equal variance).
ShadowFilter make_shadow_filter(FilterKernel kernel, float width, float density_scale, float offset = 0.0f);

// The filter that stands for a light's size (filtered_sat.h, "The filter
// from the light's size"): its box width in world units (0 for a light
// without a size: directional, point, zero angle or radius, environment) and
// whether its profile is Gaussian. `box` is the volume's world box.
struct LightFilterShape {
  float width = 0.0f;
  bool gaussian = false;
};
LightFilterShape filter_from_light(const Light& light, const Box3& box);

// The representative occluder distance for a light seen from the centre of
// `box` in direction `toward_light` (unit): a third of the box's chord
// through its centre along that direction.
float representative_occluder_distance(const Box3& box, vec3 toward_light);

}  // namespace penumbra

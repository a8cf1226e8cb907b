#pragma once
// The image-plane sweep of IPSVI (Sundén et al. 2011, section 4.1): which
// image lines are processed in which order so that every pixel comes after the
// pixels between it and the light.
//
// The light projects to an image point s'_l (a point light's position, or a
// directional light's vanishing point). Light moves across the image along
// lines through s'_l: away from it when the light is in front of the camera
// (Outward), toward it when the light is behind the camera plane (Inward:
// its rays come from the image border), and along one image direction when
// s'_l is at infinity (Parallel: a directional light across the view, or any
// directional light with an orthographic camera).
//
//  - Parallel: one sweep of horizontal or vertical lines, whichever is closer
//    to perpendicular to the light's image direction, starting at the border
//    the light comes from (the paper's directional case).
//  - Outward / Inward: four sweeps from s'_l along +x, -x, +y and -y, each over
//    the zone within 45 degrees of its axis (the paper's point-light case).
//    A directional light also takes this path under a perspective camera when
//    its vanishing point is at a finite place, since its rays then spread in
//    image space like a point light's. Pixels within `band_deg` of a zone
//    border belong to both neighbouring zones and are blended with smooth
//    weights (the paper's edge blending).
//
// Only lines that cross the given pixel rectangle (the volume's projected box)
// are planned.
#include "penumbra/base/math.h"
#include "penumbra/scene/camera.h"
#include "penumbra/scene/light.h"

#include <vector>

namespace penumbra {

enum class LightFlow : std::uint8_t { Parallel, Outward, Inward };

struct ImageLight {
  LightFlow flow = LightFlow::Parallel;
  vec2 position{0.0f};   // s'_l in pixel coordinates (Outward, Inward)
  vec2 direction{0.0f};  // Parallel: unit image direction the light travels; zero when undefined
};

// Where the light appears in a width x height image of `camera` (pixel (x, y)
// has its centre at (x + 0.5, y + 0.5)). Environment lights are not projected.
ImageLight project_light(const CameraView& camera, int width, int height, const Light& light);

struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // [x0, x1) x [y0, y1)
  bool empty() const { return x1 <= x0 || y1 <= y0; }
};

// The pixels the projected box can cover (the whole image when part of the
// box lies behind the camera), clipped to the image.
PixelRect projected_box_rect(const CameraView& camera, int width, int height, const Box3& box);

struct SweepLine {
  int coordinate = 0;  // the column (lines along y) or row (lines along x)
  int lo = 0, hi = 0;  // pixel range along the line, inclusive
};

struct SweepZone {
  int axis = 0;        // 0: lines are columns and the sweep advances in x; 1: rows, advancing in y
  int sign = 1;        // the zone lies on the + or - side of s'_l along `axis`
  int order = 1;       // +1: lines in increasing coordinate, -1: decreasing
  bool radial = false;
  vec2 light{0.0f};      // s'_l (radial zones)
  vec2 direction{0.0f};  // light direction (parallel zones)
  float band_deg = 0.0f;
  std::vector<SweepLine> lines;  // in processing order

  // Blend weight of a pixel centre in this zone, in [0, 1]; the weights of
  // the zones of a plan add up to 1 at every pixel.
  float weight(vec2 p) const;
  // Where the light's image path through pixel centre p crosses line
  // `coordinate` (the across-line coordinate, pixel units); false when it
  // does not (a line on the other side of s'_l).
  bool path_crossing(vec2 p, int coordinate, float& across) const;
};

struct SweepPlan {
  ImageLight light;
  std::vector<SweepZone> zones;
};

// `parallel_axis_hint` picks the lines when the light's image direction is
// undefined (a directional light along the view direction of an orthographic
// camera), so that the choice stays coherent between frames.
SweepPlan make_sweep_plan(const ImageLight& light, const PixelRect& rect, float band_deg, int parallel_axis_hint = 1);

}  // namespace penumbra

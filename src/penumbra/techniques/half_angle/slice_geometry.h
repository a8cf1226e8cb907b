#pragma once
// Half-angle slicing geometry (Kniss et al. 2002/2003): the volume is cut by
// planes perpendicular to the vector halfway between the view and light
// directions, so that one sweep over the slices is in order both for the eye
// (compositing) and for the light (attenuation).
//
// With v the view direction (camera forward) and l the direction the light
// travels (for a point light: from the light to the box centre):
//   v . l >= 0 (light from behind the viewer): s = normalize(v + l), slices
//     in increasing s . x, composited front to back for the eye;
//   v . l < 0 (light facing the viewer): s = normalize(l - v) ("flipped"),
//     slices in increasing s . x, which is back to front for the eye.
// Either way s . l > 0, so the light buffer advances with the slices.
#include "penumbra/base/math.h"
#include "penumbra/base/ray.h"
#include "penumbra/scene/camera.h"
#include "penumbra/scene/light.h"

namespace penumbra {

struct SliceSetup {
  vec3 axis{0.0f, 0.0f, 1.0f};  // s, unit
  vec3 light_travel{0.0f, 0.0f, -1.0f};
  bool eye_front_to_back = true;
  float first = 0.0f;    // position (s . x) of slice 0
  float spacing = 1.0f;  // between slices, along s
  int count = 0;

  PENUMBRA_HD float position(int k) const { return first + float(k) * spacing; }
};

// `slices` > 0 cuts the box's extent along s into that many slabs; 0 picks
// the spacing so that the central viewing ray crosses one slab per `step`
// (world units), like a ray caster's step.
SliceSetup make_slice_setup(const CameraView& camera, const Light& light, const Box3& box, int slices, float step);

// The points where the plane s . x = position crosses the box's 12 edges
// (the vertices of the cut polygon, unordered, a corner possibly repeated);
// returns their count.
int slice_polygon(const Box3& box, vec3 axis, float position, vec3 out[12]);

}  // namespace penumbra

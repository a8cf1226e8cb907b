#pragma once
// The part of the scene one ipsvi frame needs light for: the camera frustum
// clipped against the volume box (Sundén et al. 2011, section 5.2: "a camera
// frustum clipping of the proxy geometry against the volume bounding box,
// such that the illumination cache can be adapted to cover only the visible
// parts of the volume"), and the visible parts of the scene's planes, whose
// light rays may cross the box outside the frustum.
//
// The cache (light_cache_projection.h) is fitted to this region's
// light-space rectangle. Occluders outside it still shadow: a texel no
// visible ray writes keeps "unlit at the box entry", and the first sample
// reading it marches the light segment all the way to the box (piecewise
// integration).
//
// Texel size: a pixel's footprint at the region's centroid across the light
// (what the image resolves), longer by up to LightCacheRegion::max_aspect
// along the light-space image of the viewing direction. There the fitted
// rectangle is as long as the frustum runs deep into the volume (zoomed in
// on a volume lit from the side: a strip one image wide and a box deep), and
// the image shows depth only through surfaces seen at a slant, which the
// image foreshortens by about as much. The cache thus stays about as many
// texels as the image has pixels whatever the zoom.
#include "penumbra/base/math.h"
#include "penumbra/scene/camera.h"
#include "penumbra/scene/plane.h"
#include "penumbra/techniques/ipsvi/light_cache_projection.h"

namespace penumbra {

LightCacheRegion visible_cache_region(const CameraView& camera, int width, int height, const Box3& box,
                                      const Plane* planes, int plane_count);

}  // namespace penumbra

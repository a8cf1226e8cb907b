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
// Texel size: a pixel's footprint at the region's centroid across the light,
// longer by up to LightCacheRegion::max_aspect (4) along the light-space image
// of the viewing direction, the size capped, and the texel count held to a
// budget per image pixel (LightCacheRegion::max_texels, sweep_renderer.h),
// past which texels grow beyond the pixel. Zoomed in
// on a volume lit from the side the fitted rectangle is a strip one image wide
// and as long as the frustum runs deep into the box; texels a pixel square
// would need the strip's length in pixels along it. The long texels cost
// detail on surfaces seen at a slant, where the shadow varies along the view:
// a trade of memory against error measured in docs/ipsvi.md. Across a strip
// longer than that, the automatic grid has only the rows that cover it
// (fit_light_cache_projection's `trim`).
#include "penumbra/base/math.h"
#include "penumbra/scene/camera.h"
#include "penumbra/scene/plane.h"
#include "penumbra/techniques/ipsvi/light_cache_projection.h"

namespace penumbra {

LightCacheRegion visible_cache_region(const CameraView& camera, int width, int height, const Box3& box,
                                      const Plane* planes, int plane_count);

}  // namespace penumbra

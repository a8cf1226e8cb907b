#pragma once
// Where a world point falls in a light-space 2D buffer (IPSVI's illumination
// cache, the paper's calcIllumPos, section 4.3; half-angle's light buffer),
// and how far along its light ray it lies (the "depth" the cache stores with
// each value, section 4.4).
//
//   directional light: orthographic projection along the light direction onto
//                      a rectangle of the plane across it; depth = distance
//                      along the light from the plane touching the volume box
//                      on the light's side
//   point light outside the box: perspective projection from the light, a
//                      frustum toward the box; depth = distance to the light
//   point light inside or beside the box (a frustum would need more than a
//                      hemisphere): octahedral map of the directions, all of
//                      them or (fitted) the rectangle of the map that holds
//                      the directions toward what the camera sees
//
// The rectangle (orthographic and perspective) is the paper's "light frustum
// adaptation" (section 5.2): make_light_cache_projection fits it to the whole
// box, fit_light_cache_projection (cache_fit.h) to what the camera sees. Its
// size x rows texels may be longer along one side than along the other: the
// fitted rectangle is long where the camera frustum runs deep into the
// volume, and there the image resolves little (see cache_fit.h); across it
// the grid has only the texels the rectangle needs.
#include "penumbra/base/math.h"
#include "penumbra/base/ray.h"
#include "penumbra/scene/light.h"

#include <vector>

namespace penumbra {

enum class LightMapping : std::uint8_t { Orthographic, Perspective, Octahedral };

struct LightCacheProjection {
  LightMapping mapping = LightMapping::Orthographic;
  int size = 1;  // texels along side_u
  int rows = 1;  // texels along side_v (size for the octahedral map)
  vec3 origin{0.0f};  // orthographic: corner of the projection square at depth 0; else the light position
  vec3 axis{0.0f, 0.0f, 1.0f};  // orthographic: the light's travel direction; perspective: frustum axis;
                                // octahedral: the map's z axis (its centre's direction)
  vec3 side_u{1.0f, 0.0f, 0.0f};
  vec3 side_v{0.0f, 1.0f, 0.0f};
  vec2 scale{1.0f};  // texels per unit along side_u, side_v: orthographic world units, perspective tan
                     // units, octahedral map units (the whole map is [0, 1]^2)
  vec2 lower{0.0f};  // perspective: the tan coordinates of texel corner (0, 0); octahedral: its map coordinates
  float max_depth = 1.0f;        // the largest depth of a point of the box

  friend bool operator==(const LightCacheProjection&, const LightCacheProjection&) = default;

  // (u, v) in texel units and the depth. Points the buffer does not cover get
  // u = v = -1 (outside every texel). Written over a lane type (base/lanes.h);
  // the octahedral map runs lane by lane.
  template <class L> PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Vec3 project(const typename L::Vec3& p) const {
    using F = typename L::Float;
    using V = typename L::Vec3;
    const V q = p - V(origin);
    switch (mapping) {
      case LightMapping::Orthographic:
        return V(dot(q, V(side_u)) * scale.x, dot(q, V(side_v)) * scale.y, dot(q, V(axis)));
      case LightMapping::Perspective: {
        const F z = dot(q, V(axis));
        const F depth = length(q);
        const auto covered = z > 1e-6f * depth;
        const F u = (dot(q, V(side_u)) / z - lower.x) * scale.x;
        const F v = (dot(q, V(side_v)) / z - lower.y) * scale.y;
        return select(covered, V(u, v, depth), V(F(-1.0f), F(-1.0f), depth));
      }
      case LightMapping::Octahedral: break;
    }
    if constexpr (L::kWidth == 1) {
      return octahedral_texel(q);
    } else {
      float x[L::kWidth], y[L::kWidth], z[L::kWidth];
      L::store(q.x, x), L::store(q.y, y), L::store(q.z, z);
      for (int i = 0; i < L::kWidth; ++i) {
        const vec3 r = octahedral_texel(vec3(x[i], y[i], z[i]));
        x[i] = r.x, y[i] = r.y, z[i] = r.z;
      }
      return V(L::load(x), L::load(y), L::load(z));
    }
  }
  // The octahedral map's (u, v, depth) of q = p - origin.
  // q in the map's frame (side_u, side_v, axis): the whole map's is the
  // world's; a fitted map turns its axis toward the directions it holds.
  PENUMBRA_HD vec3 octahedral_texel(vec3 q) const {
    const vec3 local(glm::dot(q, side_u), glm::dot(q, side_v), glm::dot(q, axis));
    return vec3((octahedral_encode(local) - lower) * scale, glm::length(q));
  }
  PENUMBRA_HD vec3 project(vec3 p) const { return project<ScalarLanes>(p); }

  // The light ray through a buffer position: its origin lies at depth 0 and
  // depth grows with the ray parameter (unit direction, the light's travel
  // direction).
  PENUMBRA_HD Ray texel_ray(vec2 uv) const {
    switch (mapping) {
      case LightMapping::Orthographic:
        return Ray{origin + (uv.x / scale.x) * side_u + (uv.y / scale.y) * side_v, axis};
      case LightMapping::Perspective: {
        const vec3 d = axis + (lower.x + uv.x / scale.x) * side_u + (lower.y + uv.y / scale.y) * side_v;
        return Ray{origin, glm::normalize(d)};
      }
      case LightMapping::Octahedral: break;
    }
    const vec3 d = octahedral_decode(uv / scale + lower);
    return Ray{origin, d.x * side_u + d.y * side_v + d.z * axis};
  }

  // World size of one texel along side_u and side_v at a depth (for filters
  // given in world units).
  PENUMBRA_HD vec2 texel_world_size(float depth) const {
    switch (mapping) {
      case LightMapping::Orthographic: return vec2(1.0f) / scale;
      case LightMapping::Perspective: return vec2(glm::max(depth, 1e-6f)) / scale;
      case LightMapping::Octahedral: break;
    }
    return vec2(glm::max(depth, 1e-6f) * 3.5449077f) / scale;  // sqrt(4 pi) / texels across the whole map
  }

  // Octahedral map (Meyer et al. 2010) of a direction to [0, 1]^2 and back.
  PENUMBRA_HD static vec2 octahedral_encode(vec3 d) {
    const float l1 = glm::abs(d.x) + glm::abs(d.y) + glm::abs(d.z);
    if (!(l1 > 0.0f)) return vec2(0.5f);
    vec2 e(d.x / l1, d.y / l1);
    if (d.z < 0.0f) {
      const vec2 s(e.x >= 0.0f ? 1.0f : -1.0f, e.y >= 0.0f ? 1.0f : -1.0f);
      e = (vec2(1.0f) - vec2(glm::abs(e.y), glm::abs(e.x))) * s;
    }
    return e * 0.5f + vec2(0.5f);
  }
  PENUMBRA_HD static vec3 octahedral_decode(vec2 uv) {
    vec2 e = uv * 2.0f - vec2(1.0f);
    const float z = 1.0f - glm::abs(e.x) - glm::abs(e.y);
    if (z < 0.0f) {
      const vec2 s(e.x >= 0.0f ? 1.0f : -1.0f, e.y >= 0.0f ? 1.0f : -1.0f);
      e = (vec2(1.0f) - vec2(glm::abs(e.y), glm::abs(e.x))) * s;
    }
    return glm::normalize(vec3(e.x, e.y, z));
  }
};

// What fit_light_cache_projection fits the cache to (cache_fit.h builds it
// from the camera).
struct LightCacheRegion {
  std::vector<vec3> points;        // the hull of the visible part of the box; empty: the whole box
  vec3 centroid{0.0f};             // their centre
  std::vector<vec3> plane_points;  // corners of the visible parts of planes (their light rays cross the box)
  std::vector<vec4> bounds;        // half-spaces dot(n, x) + d >= 0 whose intersection is the visible part of
                                   // the box (empty: not known)
  vec3 long_direction{0.0f};       // texels may be longer along this direction's light-space image
  float max_aspect = 4.0f;         // at most this much longer
  float pixel = 0.0f;              // world size of a pixel at the centroid (sizes the cache when size is 0)
  double max_texels = 0.0;         // automatic size: at most this many texels (0: no bound but max_size)
  double max_map_texels = 0.0;     // the same for an octahedral map (all directions or a part)
};

// The projection of `light` fitted to `region`'s light-space bounding
// rectangle (within the box's): `size` texels per side, or with 0 texels a
// pixel wide across the rectangle's short side, at most `max_size` (and with
// region.max_texels, texels coarser by the same factor on both sides until
// the grid holds at most that many). With `trim`, where texels longer than
// max_aspect would be needed along one side, the other side gets only the
// texels (at least 16) it needs to cover the rectangle at a texel max_aspect
// times shorter, instead of `size`. An octahedral map covers all directions,
// or with `trim` the rectangle of the map that holds the directions toward
// the region (the whole map where the light lies in the visible part of the
// box, or the directions straddle one of the map's folded edges), with square
// texels, `size` along its longer side; automatic, within
// region.max_map_texels. The mapping, the axis and the depths
// depend only on the light and the box.
LightCacheProjection fit_light_cache_projection(const Light& light, const Box3& box, const LightCacheRegion& region,
                                                int size, int max_size, bool trim = false);

// Fits the projection of `light` to the whole `box` with `size` square
// texels per side. Environment lights have no direction; callers skip them.
LightCacheProjection make_light_cache_projection(const Light& light, const Box3& box, int size);

}  // namespace penumbra

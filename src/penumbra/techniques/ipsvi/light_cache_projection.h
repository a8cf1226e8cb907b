#pragma once
// Where a world point falls in a light-space 2D buffer (IPSVI's illumination
// cache, the paper's calcIllumPos, section 4.3; half-angle's light buffer),
// and how far along its light ray it lies (the "depth" the cache stores with
// each value, section 4.4).
//
//   directional light: orthographic projection along the light direction onto
//                      a square fitted to the volume box ("light frustum
//                      adaptation", section 5.2: the box's footprint, aspect
//                      ratio kept); depth = distance along the light from the
//                      plane touching the box on the light's side
//   point light outside the box: perspective projection from the light, a
//                      square frustum around the box; depth = distance to the light
//   point light inside or beside the box (a frustum would need more than a
//                      hemisphere): octahedral map of all directions
//
// Texel (i, j) covers [i, i + 1) x [j, j + 1); its centre is (i + 0.5, j + 0.5).
#include "penumbra/base/math.h"
#include "penumbra/base/ray.h"
#include "penumbra/scene/light.h"

namespace penumbra {

enum class LightMapping : std::uint8_t { Orthographic, Perspective, Octahedral };

struct LightCacheProjection {
  LightMapping mapping = LightMapping::Orthographic;
  int size = 1;
  vec3 origin{0.0f};  // orthographic: corner of the projection square at depth 0; else the light position
  vec3 axis{0.0f, 0.0f, 1.0f};  // orthographic: the light's travel direction; perspective: frustum axis
  vec3 side_u{1.0f, 0.0f, 0.0f};
  vec3 side_v{0.0f, 1.0f, 0.0f};
  float texels_per_unit = 1.0f;  // orthographic: texels per world unit; perspective: per unit of tan
  float tan_extent = 1.0f;       // perspective: half the frustum's width in tan units
  float max_depth = 1.0f;        // the largest depth of a point of the box

  // (u, v) in texel units and the depth. Points the buffer does not cover get
  // u = v = -1 (outside every texel).
  PENUMBRA_HD vec3 project(vec3 p) const {
    switch (mapping) {
      case LightMapping::Orthographic: {
        const vec3 q = p - origin;
        return vec3(glm::dot(q, side_u) * texels_per_unit, glm::dot(q, side_v) * texels_per_unit, glm::dot(q, axis));
      }
      case LightMapping::Perspective: {
        const vec3 q = p - origin;
        const float z = glm::dot(q, axis);
        const float depth = glm::length(q);
        if (!(z > 1e-6f * depth)) return vec3(-1.0f, -1.0f, depth);
        const float half = 0.5f * float(size);
        return vec3(half + glm::dot(q, side_u) / z * texels_per_unit, half + glm::dot(q, side_v) / z * texels_per_unit,
                    depth);
      }
      case LightMapping::Octahedral: break;
    }
    const vec3 q = p - origin;
    const float depth = glm::length(q);
    return vec3(octahedral_encode(q) * float(size), depth);
  }

  // The light ray through a buffer position: its origin lies at depth 0 and
  // depth grows with the ray parameter (unit direction, the light's travel
  // direction).
  PENUMBRA_HD Ray texel_ray(vec2 uv) const {
    switch (mapping) {
      case LightMapping::Orthographic:
        return Ray{origin + (uv.x / texels_per_unit) * side_u + (uv.y / texels_per_unit) * side_v, axis};
      case LightMapping::Perspective: {
        const float half = 0.5f * float(size);
        const vec3 d = axis + ((uv.x - half) / texels_per_unit) * side_u + ((uv.y - half) / texels_per_unit) * side_v;
        return Ray{origin, glm::normalize(d)};
      }
      case LightMapping::Octahedral: break;
    }
    return Ray{origin, octahedral_decode(uv / float(size))};
  }

  // World size of one texel at a depth (for filters given in world units).
  PENUMBRA_HD float texel_world_size(float depth) const {
    switch (mapping) {
      case LightMapping::Orthographic: return 1.0f / texels_per_unit;
      case LightMapping::Perspective: return glm::max(depth, 1e-6f) / texels_per_unit;
      case LightMapping::Octahedral: break;
    }
    return glm::max(depth, 1e-6f) * 3.5449077f / float(size);  // sqrt(4 pi) / size
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

// Fits the projection of `light` to `box` with `size` texels per side.
// Environment lights have no direction; callers skip them.
LightCacheProjection make_light_cache_projection(const Light& light, const Box3& box, int size);

}  // namespace penumbra

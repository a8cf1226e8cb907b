#pragma once
// Occlusion queries against the moment pyramid (Penner & Mitchell 2008,
// section 4.3, Fig. 7). Every query takes t, the normalised value whose
// exceedance counts as occlusion: for a surface point the value half a voxel
// under the surface, which for a surface on a partial-volume ramp is closer to
// the occluding material's own value than the iso-value is.
//
// Ambient occlusion: one sample in each of the first four levels, centred
// ao_offset sigmas of that level out along the normal (so each spherical
// region lies above the surface, Fig. 6), combined by max (default) or mean.
// Soft shadows: a march toward the light, four samples per iteration, with
// level log2(d tan(theta) / (2 sigma0)) at distance d (a region of radius
// 2 sigma as wide as the light's penumbra cone there, at least level 0),
// steps as long as the level's sigma, keeping the largest occlusion.
#include "penumbra/base/ray.h"
#include "penumbra/scene/light.h"
#include "penumbra/techniques/occlusion_map/moment_bounds.h"
#include "penumbra/techniques/occlusion_map/moment_pyramid_view.h"

#include <cmath>

namespace penumbra {

inline constexpr int kAmbientOcclusionLevels = 4;

template <int K> struct OcclusionQueries {
  MomentPyramidView<K> pyramid;
  Box3 box;                // the volume's world box: nothing occludes outside it
  float ao_offset = 2.0f;  // sigmas of each level along the normal
  bool ao_mean = false;    // combine the levels by mean instead of max
  float default_spread = 0.0f;  // tan(angular radius) for lights without a size

  // Share of a Gaussian region (centre c, standard deviation sigma) inside
  // the volume's box. Outside the box there is nothing, so the occlusion of a
  // region is its inside part's (what the pyramid's edge-renormalised nodes,
  // nearest to c, hold) times this share. Without it a region out past the
  // border would see the border voxels' region, and a surface facing out of
  // the volume would be occluded by what lies behind it.
  PENUMBRA_HD float inside_share(vec3 c, float sigma) const {
    const float scale = 1.0f / (glm::sqrt(2.0f) * sigma);
    float share = 1.0f;
    for (int a = 0; a < 3; ++a) {
      share *= 0.5f * (std::erf((box.upper[a] - c[a]) * scale) - std::erf((box.lower[a] - c[a]) * scale));
    }
    return glm::clamp(share, 0.0f, 1.0f);
  }

  // Occluded fraction of level `level`'s region around c for query t.
  PENUMBRA_HD float occlusion(float level, vec3 c, float t) const {
    return inside_share(c, pyramid.sigma(level)) * occluded_fraction<K>(pyramid.sample(level, c), t);
  }

  // Unoccluded fraction of the surroundings of p (unit normal n): 1 - occlusion.
  PENUMBRA_HD float ambient(vec3 p, vec3 n, float t) const {
    float worst = 0.0f, sum = 0.0f;
    const int levels = glm::min(kAmbientOcclusionLevels, pyramid.level_count);
    for (int k = 0; k < levels; ++k) {
      const vec3 q = p + n * (ao_offset * pyramid.sigma(float(k)));
      const float occlusion = this->occlusion(float(k), q, t);
      worst = glm::max(worst, occlusion);
      sum += occlusion;
    }
    return 1.0f - (ao_mean ? sum / float(levels) : worst);
  }

  // tan of the angular radius of a light seen from p. The cone query is
  // round: an anisotropic Gaussian light takes the radius of equal variance,
  // the root mean square of its two spreads.
  PENUMBRA_HD float light_spread(const Light& light, vec3 p) const {
    switch (light.type) {
      case LightType::Distant: {
        const float x = glm::min(light.angle_deg, 89.0f), y = glm::min(light.spread_y_deg(), 89.0f);
        if (x == y) return glm::tan(glm::radians(x));
        const vec2 t(glm::tan(glm::radians(x)), glm::tan(glm::radians(y)));
        return glm::sqrt(0.5f * glm::dot(t, t));
      }
      case LightType::Sphere:
      case LightType::Disk: {
        const float d = glm::length(light.position - p);
        return d > light.radius ? light.radius / glm::sqrt(d * d - light.radius * light.radius) : 1e3f;
      }
      default: return default_spread;
    }
  }

  // Unoccluded fraction toward a light: 1 - the largest occlusion along the
  // march from p (moved off the surface along n like the first AO sample)
  // toward the light, up to the light or the volume's boundary.
  PENUMBRA_HD float soft_shadow(vec3 p, vec3 n, vec3 to_light, float light_distance, float spread, float t) const {
    const vec3 start = p + n * (ao_offset * pyramid.sigma0);
    const Interval inside = intersect_box(Ray{start, to_light}, box, 0.0f, light_distance);
    if (inside.empty()) return 1.0f;
    const float lift = ao_offset * pyramid.sigma0;  // distance already travelled from p
    const float top = float(pyramid.level_count - 1);
    float worst = 0.0f;
    float s = inside.t0;
    while (s < inside.t1) {
      // Four steps per iteration, as the paper evaluates four in parallel.
      float occlusion[4];
      for (int i = 0; i < 4; ++i) {
        const float level = glm::clamp(glm::log2(glm::max((s + lift) * spread / (2.0f * pyramid.sigma0), 1.0f)),
                                       0.0f, top);
        occlusion[i] = s < inside.t1 ? this->occlusion(level, start + s * to_light, t) : 0.0f;
        s += pyramid.sigma(glm::floor(level));
      }
      worst = glm::max(worst, glm::max(glm::max(occlusion[0], occlusion[1]), glm::max(occlusion[2], occlusion[3])));
      if (worst >= 0.999f) return 0.0f;
    }
    return 1.0f - worst;
  }
};

}  // namespace penumbra

#pragma once
// How a sample or a plane hit is lit (DESIGN.md 1):
//   phase:  albedo * c * (ambient + sum_l p(cos) * L_l * V_l)
//   phong:  albedo * c * (ambient + sum_l kd max(0, n.l) L_l V_l) + sum_l ks (n.h)^s L_l V_l
//   plane:  colour * (ambient + sum_l max(0, n.l) L_l V_l)
// Every technique shares this code; each supplies only the light visibility
// V_l(x) through a Visibility functor:
//   vec3 operator()(int light, vec3 position, const LightSample&) const
// returning the volume's transmittance toward that light per colour channel,
// in [0, 1] (grey for the physical model; techniques with coloured shadows
// such as CSSM return colours). Opaque planes between a point and a light
// block it for every technique.
#include "penumbra/render/march.h"
#include "penumbra/scene/light.h"
#include "penumbra/scene/material.h"

namespace penumbra {

// True when an opaque plane (other than `skip`) lies between p and the light.
PENUMBRA_HD inline bool blocked_by_planes(const RenderView& v, vec3 p, const LightSample& ls, int skip = -1) {
  const Ray ray{p, ls.to_light};
  for (int i = 0; i < v.plane_count; ++i) {
    if (i != skip && intersect_plane(ray, v.planes[i], 0.0f, ls.distance) < kInfinity) return true;
  }
  return false;
}

// Unit shading normal from the gradient (precomputed normals when the view
// has them), facing the viewer; returns false where the gradient vanishes
// (homogeneous regions), which are then lit as if facing the light without a
// highlight.
PENUMBRA_HD PENUMBRA_FORCE_INLINE bool shading_normal(const RenderView& v, const SamplePoint& s, vec3& normal) {
  const vec3 g = v.normals.texels ? v.normals.sample(s.index) : v.volume.gradient_index(s.index);
  const float len = glm::length(g);
  if (!(len > 0.0f) || !is_finite(len)) return false;
  normal = -g / len;  // from high to low values: outward for a bright object
  if (glm::dot(normal, s.ray_dir) > 0.0f) normal = -normal;
  return true;
}

struct NoShadows {
  PENUMBRA_HD vec3 operator()(int, vec3, const LightSample&) const { return vec3(1.0f); }
};

template <class Visibility>
struct ScatteringLighting {
  const RenderView* view;
  Visibility visibility;
  Shading shading;

  PENUMBRA_HD PENUMBRA_FORCE_INLINE vec3 sample(const SamplePoint& s) const {
    const RenderView& v = *view;
    const Material& m = v.material;
    const vec3 albedo = m.albedo * s.color;
    vec3 normal(0.0f);
    const bool phong = shading == Shading::Phong;
    const bool has_normal = phong && shading_normal(v, s, normal);
    vec3 diffuse(m.ambient);
    vec3 specular(0.0f);
    for (int i = 0; i < v.light_count; ++i) {
      const LightSample ls = sample_light(v.lights[i], s.world);
      float factor = 1.0f;
      if (!phong) {
        factor = phase_hg_4pi(m.phase_g, glm::dot(ls.to_light, s.ray_dir));
      } else if (has_normal) {
        factor = m.diffuse * glm::max(0.0f, glm::dot(normal, ls.to_light));
      } else {
        factor = m.diffuse;
      }
      const float highlight =
          has_normal && m.specular > 0.0f
              ? m.specular * pow_unit(glm::max(0.0f, glm::dot(normal, glm::normalize(ls.to_light - s.ray_dir))),
                                      m.shininess)
              : 0.0f;
      if (factor <= 0.0f && highlight <= 0.0f) continue;
      if (blocked_by_planes(v, s.world, ls)) continue;
      const vec3 visible = visibility(i, s.world, ls) * ls.radiance;
      diffuse += factor * visible;
      specular += highlight * visible;
    }
    return albedo * diffuse + specular;
  }

  PENUMBRA_HD vec3 plane(const PlaneHit& h) const {
    const RenderView& v = *view;
    const Plane& p = v.planes[h.plane];
    // The side of the plane the viewer sees.
    const vec3 normal = glm::dot(p.normal, h.ray_dir) < 0.0f ? p.normal : -p.normal;
    vec3 sum(v.material.ambient);
    for (int i = 0; i < v.light_count; ++i) {
      const LightSample ls = sample_light(v.lights[i], h.position);
      const float cosine = glm::dot(normal, ls.to_light);
      if (cosine <= 0.0f) continue;
      if (blocked_by_planes(v, h.position, ls, h.plane)) continue;
      sum += cosine * visibility(i, h.position, ls) * ls.radiance;
    }
    return p.color * sum;
  }
};

// Unlit emission-absorption: the TF colour is the emitted radiance; planes
// show their colour.
struct EmissionLighting {
  const RenderView* view;
  PENUMBRA_HD vec3 sample(const SamplePoint& s) const { return s.color; }
  PENUMBRA_HD vec3 plane(const PlaneHit& h) const { return view->planes[h.plane].color; }
};

}  // namespace penumbra

#pragma once
// The per-pixel and per-texel work of one slice in half-angle slicing (Kniss
// et al. 2002, 2003): where a viewing ray or a light ray crosses the slice
// plane it takes one sample; the eye buffer composites it lit by the light
// buffer, the light buffer is attenuated by it. The model is IPSVI's
// (techniques/ipsvi/forward_scattering.h): direct and diffuse light, the
// diffuse part attenuated by what leaves the cone and blurred per slice.
#include "penumbra/render/lighting.h"
#include "penumbra/render/march.h"
#include "penumbra/techniques/half_angle/slice_geometry.h"
#include "penumbra/techniques/ipsvi/forward_scattering.h"
#include "penumbra/techniques/ipsvi/light_cache_projection.h"

#include <cstdint>

namespace penumbra {

// A viewing or light ray with its offsets along the slicing axis.
struct SlicedRay {
  vec3 origin{0.0f};
  vec3 direction{0.0f};
  float origin_s = 0.0f;     // s . origin
  float direction_s = 0.0f;  // s . direction
  float t_max = kInfinity;   // viewing rays: the nearest opaque plane

  // The ray parameter where it crosses the slice at `position` (or -1).
  PENUMBRA_HD float crossing(float position) const {
    if (!(glm::abs(direction_s) > 1e-6f)) return -1.0f;
    return (position - origin_s) / direction_s;
  }
};

// An eye-buffer pixel: front to back, `transmittance` is what the colour
// still lets through; back to front it is the product over what has been
// composited over the base (background or plane).
struct EyePixel {
  vec3 color{0.0f};
  float transmittance = 1.0f;
  bool plane_done = false;
};

struct HalfAngleKernel {
  const RenderView* view = nullptr;    // lights[0] is the light of this pass
  const RenderView* shadow = nullptr;  // with the shadow TF: what attenuates light
  bool separate_shadow_tf = false;
  SliceSetup slices;
  LightCacheProjection projection;  // the light buffer's mapping
  const vec4* light = nullptr;      // light buffer: (direct, diffuse rgb) per texel
  ForwardScattering scattering;

  // Bilinear light-buffer read; outside the buffer nothing shadows.
  PENUMBRA_HD vec4 read_light(vec2 uv) const {
    const int n = projection.size;
    if (!(uv.x >= 0.0f && uv.y >= 0.0f && uv.x <= float(n) && uv.y <= float(n))) return vec4(1.0f);
    const float x = glm::clamp(uv.x - 0.5f, 0.0f, float(n - 1));
    const float y = glm::clamp(uv.y - 0.5f, 0.0f, float(n - 1));
    const int x0 = int(x), y0 = int(y);
    const int x1 = glm::min(x0 + 1, n - 1), y1 = glm::min(y0 + 1, n - 1);
    const float fx = x - float(x0), fy = y - float(y0);
    return glm::mix(glm::mix(light[x0 + n * y0], light[x1 + n * y0], fx),
                    glm::mix(light[x0 + n * y1], light[x1 + n * y1], fx), fy);
  }

  // Distance along the light ray through p between two slices (<= 0: the
  // light does not advance with the slices there).
  PENUMBRA_HD float light_step(vec3 p) const {
    const vec3 w = light_travel(p);
    const float c = glm::dot(w, slices.axis);
    return c > 1e-4f ? slices.spacing / c : -1.0f;
  }

  PENUMBRA_HD vec3 light_travel(vec3 p) const {
    const Light& l = view->lights[0];
    return l.at_infinity() ? glm::normalize(l.direction) : -sample_light(l, p).to_light;
  }

  // Light visibility at p: the buffer as the slices before this one left it,
  // attenuated over half a slab by the medium at p (extinction sigma, shadow
  // TF colour) so that a sample sees the light at its own depth.
  PENUMBRA_HD vec3 visibility(vec3 p, float sigma, vec3 color) const {
    const vec3 proj = projection.project(p);
    const vec4 l = read_light(vec2(proj));
    const float half = 0.5f * light_step(p);
    float direct = l.x;
    vec3 diffuse(l.y, l.z, l.w);
    if (half > 0.0f && sigma > 0.0f) {
      direct *= exp_nonpositive(-sigma * half);
      if (scattering.has_diffuse()) {
        const vec3 tau = scattering.diffuse_extinction(color, sigma) * half;
        diffuse *= vec3(exp_nonpositive(-tau.r), exp_nonpositive(-tau.g), exp_nonpositive(-tau.b));
      }
    }
    return scattering.visibility(direct, diffuse);
  }

  // True when the macrocell around index-space point i can hold extinction.
  PENUMBRA_HD static bool occupied(const RenderView& v, vec3 i) { return v.majorant_at(i) > 0.0f; }

  PENUMBRA_HD bool inside(vec3 p) const {
    return view->box.contains(p) && inside_clip_planes(p, view->clip_planes, view->clip_plane_count);
  }
};

// The sample of slice `k` on a viewing ray, composited into its pixel.
template <class Sampler>
PENUMBRA_HD void eye_slice_sample(const HalfAngleKernel& k, const Sampler& sampler, const SlicedRay& ray, int slice,
                                  EyePixel& px, std::uint64_t& samples) {
  const RenderView& v = *k.view;
  if (k.slices.eye_front_to_back && px.transmittance <= 1.0f - v.ert_threshold) return;
  const float t = ray.crossing(k.slices.position(slice));
  if (!(t > 0.0f && t < ray.t_max)) return;
  // A ray crossing the slices against the compositing order cannot be
  // composited by them (only at extreme fields of view).
  if ((ray.direction_s > 0.0f) != k.slices.eye_front_to_back) return;
  const vec3 p = ray.origin + t * ray.direction;
  if (!k.inside(p)) return;
  const vec3 index = v.volume.index_from_world(p);
  if (!HalfAngleKernel::occupied(v, index)) return;
  ++samples;
  const float value = sampler(index);
  const vec4 c = Sampler::kAlwaysFinite ? v.tf.lookup_finite(value) : v.tf.lookup(value);
  if (!(c.a > 0.0f)) return;
  const vec4 cs = !k.separate_shadow_tf ? c : (Sampler::kAlwaysFinite ? k.shadow->tf.lookup_finite(value)
                                                                      : k.shadow->tf.lookup(value));
  const float alpha = 1.0f - exp_nonpositive(-c.a * k.slices.spacing / glm::abs(ray.direction_s));
  const vec3 visibility = k.visibility(p, cs.a, vec3(cs));
  const vec3 lit = ScatteringLighting<FixedVisibility>{&v, {visibility}, v.material.shading}.sample(
      SamplePoint{p, index, value, vec3(c), c.a, ray.direction});
  if (k.slices.eye_front_to_back) {
    px.color += (px.transmittance * alpha) * lit;
  } else {
    px.color = alpha * lit + (1.0f - alpha) * px.color;
  }
  px.transmittance *= 1.0f - alpha;
}

// Slice `k` attenuating one light-buffer texel (its light ray `ray`).
template <class Sampler>
PENUMBRA_HD void light_slice_sample(const HalfAngleKernel& k, const Sampler& sampler, const SlicedRay& ray, int slice,
                                    vec4& texel, std::uint64_t& samples) {
  if (!(ray.direction_s > 1e-4f)) return;
  const float t = ray.crossing(k.slices.position(slice));
  if (!(t > 0.0f)) return;
  const RenderView& v = *k.shadow;
  const vec3 p = ray.origin + t * ray.direction;
  if (!k.inside(p)) return;
  const vec3 index = v.volume.index_from_world(p);
  if (!HalfAngleKernel::occupied(v, index)) return;
  ++samples;
  const float value = sampler(index);
  const vec4 c = Sampler::kAlwaysFinite ? v.tf.lookup_finite(value) : v.tf.lookup(value);
  if (!(c.a > 0.0f)) return;
  const float length = k.slices.spacing / ray.direction_s;
  texel.x *= exp_nonpositive(-c.a * length);
  if (k.scattering.has_diffuse()) {
    const vec3 tau = k.scattering.diffuse_extinction(vec3(c), c.a) * length;
    texel.y *= exp_nonpositive(-tau.r);
    texel.z *= exp_nonpositive(-tau.g);
    texel.w *= exp_nonpositive(-tau.b);
  }
}

}  // namespace penumbra

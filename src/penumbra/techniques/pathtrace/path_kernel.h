#pragma once
// One light path from the camera (the per-sample kernel of `pathtrace`).
// Free flights by delta tracking; at every scattering event (volume or
// plane) next-event estimation sends one sample toward every light, with
// transmittance by ratio tracking; the path then continues by sampling the
// phase function (volume) or a cosine lobe (plane), weighted by the albedo,
// until `max_bounces` events or Russian roulette end it.
//
// The estimators, in the units of light.h (a light of intensity I delivers
// 4 pi I; LightDirectionSample::weight is radiance / pdf / 4 pi):
//   volume vertex  albedo * c * sum_l phase_hg_4pi(g, cos) * weight_l * T_l
//   plane vertex   colour * sum_l max(0, n . l) * weight_l * T_l
//                  (Lambertian with albedo colour / 4, so a bounce off it
//                  carries colour / 4)
// which are the shared lighting code's formulas with area lights sampled
// instead of taken at their centre. Lights are not visible to rays (as in
// every technique) except environment lights, which camera rays that escape
// see together with the background; after a scattering event environment
// light arrives only through next-event estimation, so nothing is counted
// twice. Opaque planes block light and paths. The scene's `ambient` is not
// physical and is ignored. The scene's meshes are media of their own added to
// the volume's (mesh_tracking.h), scattering with material.albedo times their
// TF colour like the volume; convolution's surface highlight has no
// counterpart here. A mesh's transport colour (chromatic attenuation, like
// `ambient` an appearance control outside the physical model) colours the
// light on next-event estimation's shadow rays only; paths themselves fly
// through the grey extinction.
#include "penumbra/base/rng.h"
#include "penumbra/render/lighting.h"
#include "penumbra/scene/light_sampling.h"
#include "penumbra/techniques/pathtrace/free_flight.h"
#include "penumbra/techniques/pathtrace/mesh_tracking.h"
#include "penumbra/techniques/pathtrace/phase_sampling.h"

#include <cstdint>

namespace penumbra {

enum class ScatteringMode : std::uint8_t {
  Single,    // one scattering event lit by transmittance only: converges to shadow-rays
  Multiple,  // full multiple scattering
};

struct PathSettings {
  ScatteringMode mode = ScatteringMode::Multiple;
  int max_bounces = 64;  // scattering events per path (multiple mode)
  int roulette_from = 3;  // Russian roulette from this many events on
};

struct PathSample {
  vec3 radiance{0.0f};
  bool hit = false;  // the camera ray met the medium or a plane (its mean is the pixel's opacity)
};

// An independent random stream per (seed, pixel, sample), so an image does
// not depend on threads, tiles or how the samples are split into passes.
PENUMBRA_HD inline Pcg32 path_rng(std::uint32_t seed, std::uint32_t pixel, std::uint32_t sample) {
  return Pcg32(mix_bits((std::uint64_t(seed) << 32) | pixel), mix_bits(sample + 0x9e3779b97f4a7c15ULL));
}

// Nearest opaque plane along the ray other than `skip` (the plane a path
// leaves from); its index or -1.
PENUMBRA_HD inline int nearest_plane_except(const RenderView& v, const Ray& ray, int skip, float& t_hit) {
  int hit = -1;
  t_hit = kInfinity;
  for (int i = 0; i < v.plane_count; ++i) {
    if (i == skip) continue;
    const float t = intersect_plane(ray, v.planes[i], 0.0f, t_hit);
    if (t < t_hit) {
      t_hit = t;
      hit = i;
    }
  }
  return hit;
}

// What a camera ray that leaves the scene sees: the background plus every
// environment light.
PENUMBRA_HD inline vec3 escaped_radiance(const RenderView& v) {
  vec3 sum = v.background;
  for (int i = 0; i < v.light_count; ++i) {
    if (v.lights[i].type == LightType::Environment) sum += v.lights[i].color * v.lights[i].intensity;
  }
  return sum;
}

template <class Sampler>
struct PathKernel {
  const RenderView* view;     // the medium paths fly through, planes, lights, material
  const RenderView* shadows;  // the medium toward lights (the shadow TF, if the scene has one)
  Sampler sampler;
  PathSettings settings;
  MeshesView meshes{};  // the scene's meshes with their BVHs (count 0: none)

  // Next-event estimation at p: one sample per light, each scaled by
  // factor(to_light) (the phase function or the cosine) and by the
  // transmittance toward it; planes other than `skip_plane` block.
  template <class Factor>
  PENUMBRA_HD vec3 direct_light(vec3 p, int skip_plane, const Factor& factor, Pcg32& rng,
                                std::uint64_t& lookups) const {
    const RenderView& v = *view;
    vec3 sum(0.0f);
    for (int i = 0; i < v.light_count; ++i) {
      const vec2 u(rng.next_float(), rng.next_float());
      const LightDirectionSample ls = sample_light_direction(v.lights[i], p, u);
      if (!(max_component(ls.weight) > 0.0f)) continue;
      const float f = factor(ls.to_light);
      if (!(f > 0.0f)) continue;
      if (blocked_by_planes(v, p, LightSample{ls.to_light, ls.distance, ls.weight}, skip_plane)) continue;
      vec3 transmittance(ratio_tracking(*shadows, sampler, Ray{p, ls.to_light}, ls.distance, rng, lookups));
      if (meshes.count > 0 && transmittance.x > 0.0f) {
        transmittance *= mesh_ratio_tracking(meshes, Ray{p, ls.to_light}, ls.distance, rng, lookups);
      }
      sum += (f * transmittance) * ls.weight;
    }
    return sum;
  }

  // Whether the path goes on after `events` scattering events; applies
  // Russian roulette to `throughput`.
  PENUMBRA_HD bool continues(int events, vec3& throughput, Pcg32& rng) const {
    if (settings.mode == ScatteringMode::Single || events >= settings.max_bounces) return false;
    const float strongest = max_component(throughput);
    if (!(strongest > 0.0f)) return false;
    if (events >= settings.roulette_from) {
      const float survival = glm::min(strongest, 0.95f);
      if (rng.next_float() >= survival) return false;
      throughput /= survival;
    }
    return true;
  }

  PENUMBRA_HD PathSample trace(Ray ray, Pcg32& rng, std::uint64_t& lookups) const {
    const RenderView& v = *view;
    const float g = v.material.phase_g;
    PathSample out;
    vec3 throughput(1.0f);
    int skip_plane = -1;
    for (int events = 0;;) {
      float t_plane = kInfinity;
      const int plane = nearest_plane_except(v, ray, skip_plane, t_plane);
      const Interval medium = volume_interval(v, ray, 0.0f, t_plane);
      Collision c;
      bool collided = delta_tracking(v, sampler, ray, medium.t0, medium.t1, rng, c, lookups);
      if (meshes.count > 0 && mesh_delta_tracking(meshes, ray, collided ? c.t : t_plane, rng, c, lookups)) {
        collided = true;
      }
      if (events == 0) out.hit = collided || plane >= 0;
      if (collided) {
        const vec3 p = ray.at(c.t);
        const vec3 travel = ray.direction;
        throughput *= v.material.albedo * c.color;
        const auto phase = [&](vec3 to_light) { return phase_hg_4pi(g, glm::dot(to_light, travel)); };
        out.radiance += throughput * direct_light(p, -1, phase, rng, lookups);
        if (!continues(++events, throughput, rng)) break;
        const vec2 u(rng.next_float(), rng.next_float());
        ray = Ray{p, sample_hg(travel, g, u)};
        skip_plane = -1;
      } else if (plane >= 0) {
        const vec3 p = ray.at(t_plane);
        const Plane& surface = v.planes[plane];
        const vec3 normal = glm::dot(surface.normal, ray.direction) < 0.0f ? surface.normal : -surface.normal;
        const auto cosine = [&](vec3 to_light) { return glm::dot(normal, to_light); };
        out.radiance += throughput * surface.color * direct_light(p, plane, cosine, rng, lookups);
        throughput *= 0.25f * surface.color;
        if (!continues(++events, throughput, rng)) break;
        const vec2 u(rng.next_float(), rng.next_float());
        ray = Ray{p, sample_cosine_hemisphere(normal, u)};
        skip_plane = plane;
      } else {
        if (events == 0) out.radiance += escaped_radiance(v);
        break;
      }
    }
    return out;
  }
};

}  // namespace penumbra

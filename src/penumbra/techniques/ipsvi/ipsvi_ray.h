#pragma once
// One viewing ray of IPSVI (Sundén et al. 2011, Listing 4.1): while the ray
// composites front to back along the view, every sample
//   1. projects itself into the illumination cache (calcIllumPos) and reads
//      the light that reached the previous sweep planes there,
//   2. brings that light to its own position: the piecewise integration of
//      the light-ray segment back to where the cached value holds (4.4), or,
//      without it, its own extinction over one step (the paper's composite of
//      the sample's colour into illumIn),
//   3. is lit with it through the engine's shading (lighting.h), and
//   4. joins a run of samples in the same cache texel; when the ray moves on
//      to another texel the run is written (storeIllum when illumPos changes).
// Steps 1-3 cost a light segment and are skipped for samples that are not
// shaded (transparent, or behind the terminated colour): with piecewise
// integration a write needs only the run's depth, the texel's own light ray
// being carried forward to it after the block (sweep_renderer.cpp).
// The ray marches the whole volume: what hides behind an opaque front may
// still shadow the lines after it (Fig. 5), so early ray termination only
// stops the colour, unless the ERT extension (early_termination.h) gives an
// exit depth after which nothing is needed.
//
// Traversal order (4.4): samples are visited away from the light along the
// ray, front to back beyond the light's closest approach to the ray and back
// to front before it, so that a sample can continue the light of the previous
// sample of the same ray when both fall in one cache texel (what makes a light
// on the viewing ray, or a directional light along it, work).
#include "penumbra/render/lighting.h"
#include "penumbra/render/march.h"
#include "penumbra/techniques/ipsvi/forward_scattering.h"
#include "penumbra/techniques/ipsvi/illumination_cache.h"
#include "penumbra/techniques/ipsvi/light_cache_projection.h"
#include "penumbra/techniques/ipsvi/light_model.h"
#include "penumbra/techniques/ipsvi/light_segment.h"
#include "penumbra/techniques/ipsvi/segment_tape.h"

#include <cstdint>

namespace penumbra {

struct IpsviKernel {
  const RenderView* view = nullptr;    // lights[0] is the light of this sweep
  const RenderView* shadow = nullptr;  // the same with the shadow TF: light attenuation
  bool separate_shadow_tf = false;
  LightCacheProjection projection;
  IlluminationCacheView cache;
  ForwardScattering scattering;
  bool piecewise = true;
  // The paper's light model (light_model.h): the direct light's colour
  // (the cache's colour channel), a(s) and the cone-mean phase.
  bool paper = false;
  ConePhase cone_phase;
};

struct IpsviRayCounts {
  std::uint64_t view_samples = 0;   // samples of the viewing rays
  std::uint64_t light_samples = 0;  // samples of piecewise-integration segments
  std::uint64_t exact_plane_rays = 0;  // plane hits on a shadow edge that marched their own light ray
  std::uint64_t packet_segments = 0;   // light segments taken from the tape (segment_tape.h)
};

// Below this sine of the angle between the light and the viewing ray a
// sample continues the previous sample's light (ipsvi_light_at).
inline constexpr float kAlongRaySine = 0.1f;

// A plane hit whose four cache texels, each continued to it, differ by more
// than this in transmittance lies on a shadow edge; it marches its own light
// ray to the box instead (plane_light). Measured in docs/ipsvi.md.
inline constexpr float kPlaneEdgeSpread = 0.02f;

// What one ray remembers between its samples.
struct RayCacheState {
  vec3 ray_direction{0.0f};
  // The previous sample's light (in-ray propagation).
  int texel = -1;
  float depth = 0.0f;
  float direct = 1.0f;
  vec3 color{1.0f};
  // The open run of samples in one texel: weighted sums.
  int run_texel = -1;
  float run_weight = 0.0f;
  float run_direct = 0.0f;
  float run_depth = 0.0f;
  vec3 run_diffuse{0.0f};
  vec3 run_color{0.0f};
  // Light segments recorded or replayed (segment_tape.h); null: each
  // sample marches its own.
  SegmentTape* tape = nullptr;
  // The colour has reached the ERT opacity: with piecewise integration the
  // samples after it only join the cache's runs (their depths), so they read
  // no value and no colour, and a recording ray stops (ipsvi_march). Up to
  // `exit_t` (the ERT extension's exit depth, +inf without it).
  bool colour_done = false;
  float exit_t = kInfinity;

  PENUMBRA_HD bool recording() const { return tape && tape->recording(); }
};

// Ray parameter of the light's closest approach to the ray; for a light at
// infinity -inf when its light travels along the ray, +inf against it.
PENUMBRA_HD inline float light_parameter(const Light& light, const Ray& ray) {
  if (light.at_infinity()) return glm::dot(light.direction, ray.direction) >= 0.0f ? -kInfinity : kInfinity;
  return glm::dot(light.position - ray.origin, ray.direction);
}

// Writes the open run to the cache: its weight, mean depth and (without
// piecewise integration) mean light. With piecewise integration the light is
// not taken from the samples: the resolve step (sweep_renderer.cpp) carries
// each written texel's own light ray forward to the mean depth.
PENUMBRA_HD inline void flush_run(const IpsviKernel& k, RayCacheState& st) {
  if (st.run_texel >= 0 && st.run_weight > 0.0f && !st.recording()) {
    const float inv = 1.0f / st.run_weight;
    k.cache.write(st.run_texel, st.run_weight, st.run_direct * inv, st.run_depth * inv, st.run_diffuse * inv,
                  st.run_color * inv);
  }
  st.run_texel = -1;
  st.run_weight = st.run_direct = st.run_depth = 0.0f;
  st.run_diffuse = st.run_color = vec3(0.0f);
}

// The light reaching world point p (projection proj = (u, v, depth)), whose
// own extinction is `sigma` with TF colour `color` (the shadow TF's). With
// the paper's light model the direct light's colour (Eq. 3) is carried
// beside the grey transmittance, through the same segments.
//
// The four texels around p were written at different depths (different
// lines); each is continued from its own depth to p's, with one march back
// toward the light that reports the optical depth at each of those depths,
// before they are blended. (Blending the depths instead would let a texel
// written far behind p lend its shorter segment to one written before the
// structure p sits in.) Texels already ahead of p are left out.
// `spread`, when given, receives the largest difference between the texels'
// direct light once continued to p (0 for one texel).
template <class Sampler>
PENUMBRA_HD CachedLight ipsvi_light_at(const IpsviKernel& k, const Sampler& sampler, vec3 p, vec3 proj, float sigma,
                                       vec3 color, RayCacheState& st, IpsviRayCounts& counts,
                                       float* spread = nullptr) {
  const RenderView& v = *k.view;
  const ForwardScattering& fs = k.scattering;
  const vec2 uv(proj);
  const float here = proj.z;
  // Outside the cache: nothing in the way.
  if (!k.cache.covers(uv)) return CachedLight{1.0f, here, vec3(1.0f), vec3(1.0f)};
  const int texel = k.cache.texel_index(uv);
  int taps[4];
  float weights[4];
  k.cache.taps(uv, taps, weights);
  float base_direct[5], lengths[5];
  vec3 base_color[5];
  float weight_sum = 0.0f, mean_depth = 0.0f, newest = -kInfinity;
  int n = 0;
  for (int i = 0; i < 4; ++i) {
    const vec2 t = k.cache.state[taps[i]];
    if (!(weights[i] > 0.0f) || t.y > here) continue;
    base_direct[n] = t.x;
    if (k.paper) base_color[n] = vec3(k.cache.color[taps[i]]);
    lengths[n] = here - t.y;
    weights[n] = weights[i];
    weight_sum += weights[i];
    mean_depth += weights[i] * t.y;
    newest = glm::max(newest, t.y);
    ++n;
  }
  if (n == 0) {  // every texel is ahead of p: take them as they are
    const CachedLight c = k.cache.read(uv, false);
    base_direct[0] = c.direct;
    if (k.paper) base_color[0] = k.cache.color_at(uv);
    lengths[0] = 0.0f;
    weights[0] = weight_sum = 1.0f;
    mean_depth = newest = here;
    n = 1;
  }
  mean_depth /= weight_sum;
  // Where the light runs almost along the viewing ray, p's light ray crosses
  // few sweep planes and the cache is far behind; the previous sample of this
  // ray, in the same texel and nearer the light, then carries the light
  // instead (the case the traversal order is for). Elsewhere the cache is
  // better: the previous sample lies beside p's light ray, and in a dense
  // medium that lateral offset matters. (Only without the diffuse part, whose
  // spread is applied per cache read.)
  const LightSample ls = sample_light(v.lights[0], p);
  const bool along_ray = glm::length(glm::cross(ls.to_light, st.ray_direction)) < kAlongRaySine;
  if (along_ray && !fs.has_diffuse() && st.texel == texel && st.depth > newest && st.depth <= here) {
    base_direct[0] = st.direct;
    base_color[0] = st.color;
    lengths[0] = here - st.depth;
    weights[0] = weight_sum = 1.0f;
    n = 1;
  }
  const int diffuse_slot = n;
  lengths[diffuse_slot] = here - mean_depth;
  const int checkpoints = fs.has_diffuse() ? n + 1 : n;
  OpticalDepth tau[5];
  if (k.piecewise && st.recording()) {
    // Only where the light is needed from here on is recorded; the light
    // itself is not (segment_tape.h).
    st.tape->record(p, ls.to_light, lengths, checkpoints);
    st.texel = texel;
    st.depth = here;
    return CachedLight{1.0f, here, vec3(1.0f), vec3(1.0f)};
  }
  if (k.piecewise && st.tape && st.tape->replay(tau, checkpoints)) {
    // marched as packets
  } else if (k.piecewise) {
    if (k.paper) {
      light_segment_depths<true>(*k.shadow, sampler, p, ls.to_light, lengths, checkpoints, fs, tau,
                                 counts.light_samples);
    } else {
      light_segment_depths(*k.shadow, sampler, p, ls.to_light, lengths, checkpoints, fs, tau, counts.light_samples);
    }
  } else {
    const vec3 ext = fs.has_diffuse() ? fs.diffuse_extinction(color, sigma) : vec3(0.0f);
    for (int i = 0; i < checkpoints; ++i) {
      const float length = glm::min(lengths[i], v.step);
      tau[i].direct = sigma * length;
      tau[i].diffuse = ext * length;
      // Listing 4.1: the sample's own colour composited into the light.
      if (k.paper) {
        tau[i].emitted = (1.0f - exp_nonpositive(-tau[i].direct)) * glm::clamp(color, vec3(0.0f), vec3(1.0f));
      }
    }
  }
  CachedLight out;
  out.depth = here;
  out.direct = 0.0f;
  for (int i = 0; i < n; ++i) out.direct += weights[i] * base_direct[i] * exp_nonpositive(-tau[i].direct);
  out.direct /= weight_sum;
  if (spread) {
    float lo = 1.0f, hi = 0.0f;
    for (int i = 0; i < n; ++i) {
      const float d = base_direct[i] * exp_nonpositive(-tau[i].direct);
      lo = glm::min(lo, d);
      hi = glm::max(hi, d);
    }
    *spread = glm::max(hi - lo, 0.0f);
  }
  if (k.paper) {
    out.color = vec3(0.0f);
    for (int i = 0; i < n; ++i) {
      out.color += weights[i] * (base_color[i] * exp_nonpositive(-tau[i].direct) + tau[i].emitted);
    }
    out.color /= weight_sum;
  }
  if (fs.has_diffuse()) {
    const vec2 spread = glm::sqrt(lengths[diffuse_slot] * fs.spread_per_length) / k.projection.texel_world_size(here);
    const vec3 t = tau[diffuse_slot].diffuse;
    out.diffuse = k.cache.read_diffuse(uv, spread) *
                  vec3(exp_nonpositive(-t.r), exp_nonpositive(-t.g), exp_nonpositive(-t.b));
  }
  st.texel = texel;
  st.depth = out.depth;
  st.direct = out.direct;
  st.color = out.color;
  return out;
}

// The visibility V the shading takes for light `light` at p, seen along
// ray_dir: the grey model's blend by the global albedo, or the paper's by
// a(s) per channel, `albedo` (light_model.h: the sample's, or the albedo
// parameter for a plane), with the cone-mean phase for the diffuse part
// (`phase`: false for a plane or Phong shading, whose factor is no phase).
PENUMBRA_HD inline vec3 ipsvi_visibility(const IpsviKernel& k, const CachedLight& light, vec3 albedo, vec3 p,
                                         vec3 ray_dir, bool phase) {
  if (!k.paper) return k.scattering.visibility(light.direct, light.diffuse);
  if (!k.scattering.has_diffuse()) return light.color;
  const float ratio = phase ? k.cone_phase.at(glm::dot(sample_light(k.view->lights[0], p).to_light, ray_dir)) : 1.0f;
  return paper_visibility(light.color, light.diffuse, albedo, ratio);
}

// The light reaching plane hit q. A floor far below the volume reads texels
// whose light rays pass up to a texel (up to 4 along the view, cache_fit.h)
// beside its own, written after the occluders: across a shadow edge the
// bilinear read spreads the edge over that footprint, seen as a one-texel
// bright line along the shadow's inside (issue 21). Where the four texels
// disagree (kPlaneEdgeSpread) q's own light ray is marched to the box
// instead, as shadow-rays does; the diffuse part stays the cache's. So does
// a plane hit outside the cache whose light ray crosses the box: an
// octahedral map holds only the directions toward the visible part of the
// box (cache_fit.h), and a floor point may lie in another direction.
template <class Sampler>
PENUMBRA_HD CachedLight plane_light(const IpsviKernel& k, const Sampler& sampler, vec3 q, RayCacheState& st,
                                    IpsviRayCounts& counts) {
  float spread = 0.0f;
  // Plane hits march their segments themselves (they are not recorded).
  SegmentTape* const tape = st.tape;
  st.tape = nullptr;
  const vec3 proj = k.projection.project(q);
  CachedLight light = ipsvi_light_at(k, sampler, q, proj, 0.0f, vec3(0.0f), st, counts, &spread);
  st.tape = tape;
  const LightSample ls = sample_light(k.view->lights[0], q);
  const bool outside = !k.cache.covers(vec2(proj)) &&
                       !volume_interval(*k.shadow, Ray{q, ls.to_light}, 0.0f, ls.distance).empty();
  if (!outside && (!k.piecewise || !(spread > kPlaneEdgeSpread))) return light;
  std::uint64_t& samples = counts.light_samples;
  const OpticalDepth tau =
      k.paper ? light_segment_depth<true>(*k.shadow, sampler, q, ls.to_light, ls.distance, k.scattering, samples)
              : light_segment_depth(*k.shadow, sampler, q, ls.to_light, ls.distance, k.scattering, samples);
  light.direct = exp_nonpositive(-tau.direct);
  light.color = vec3(light.direct) + tau.emitted;
  ++counts.exact_plane_rays;
  return light;
}

// Adds a sample at cache position uv and depth to the ray's run for its
// texel, writing the previous run when the texel changes. `light` (the
// sample's light) is only used without piecewise integration.
PENUMBRA_HD inline void add_to_run(const IpsviKernel& k, vec2 uv, float depth, const CachedLight& light,
                                   RayCacheState& st) {
  const int texel = k.cache.texel_index(uv);
  if (texel != st.run_texel) {
    flush_run(k, st);
    st.run_texel = texel;
  }
  // Samples near the texel centre's light ray count most.
  const vec2 f = glm::abs(uv - (glm::floor(uv) + vec2(0.5f)));
  const float w = (1.0f - f.x) * (1.0f - f.y);
  st.run_weight += w;
  st.run_depth += w * depth;
  st.run_direct += w * light.direct;
  st.run_diffuse += w * light.diffuse;
  if (k.paper) st.run_color += w * light.color;
}

// Marches samples of [ta, tb] along `ray` away from the light: front to back
// when `forward`, else back to front (along the reversed ray).
// shade(t, sample, length, visibility) receives each sample in visiting order
// and returns false to stop; visibility() computes the sample's light, which
// costs a light segment, so a sample that is transparent or behind the
// terminated colour does not ask for it: with piecewise integration the
// cache writes march the texels' own light rays (at resolve) and need nothing
// from the samples but their depths.
template <class Sampler, class Shade>
PENUMBRA_HD void ipsvi_march(const IpsviKernel& k, const Sampler& sampler, const Ray& ray, float ta, float tb,
                             bool forward, float offset, RayCacheState& st, IpsviRayCounts& counts, Shade&& shade) {
  if (!(ta < tb)) return;
  const RenderView& v = *k.view;
  const Ray walk = forward ? ray : Ray{ray.at(tb), -ray.direction};
  const SampleGrid grid(forward ? Interval{ta, tb} : Interval{0.0f, tb - ta}, v.step, offset);
  const vec3 o = v.volume.index_from_world(walk.origin);
  const vec3 d = walk.direction / v.volume.spacing;
  const TransferFunctionView tf = v.tf;
  const TransferFunctionView shadow_tf = k.shadow->tf;
  SampleCursor cursor(v, walk, grid);
  int kk;
  float t;
  while (cursor.next(kk, t)) {
    ++counts.view_samples;
    if (st.colour_done && k.piecewise) {
      // Behind the terminated colour nothing asks for light: a recording
      // ray is done, and otherwise the sample only extends the open run,
      // as below with the light unasked.
      if (st.recording()) break;
      const vec3 proj = k.projection.project(walk.at(t));
      if (k.cache.covers(vec2(proj))) add_to_run(k, vec2(proj), proj.z, CachedLight{}, st);
      if (!((forward ? t : tb - t) < st.exit_t)) break;
      continue;
    }
    const vec3 index = o + t * d;
    const float value = sampler(index);
    const vec4 c = Sampler::kAlwaysFinite ? tf.lookup_finite(value) : tf.lookup(value);
    const vec4 cs = !k.separate_shadow_tf ? c : (Sampler::kAlwaysFinite ? shadow_tf.lookup_finite(value)
                                                                        : shadow_tf.lookup(value));
    const vec3 p = walk.at(t);
    const vec3 proj = k.projection.project(p);
    CachedLight light;
    bool lit = false;
    auto visibility = [&]() {
      if (!lit) {
        light = ipsvi_light_at(k, sampler, p, proj, cs.a, vec3(cs), st, counts);
        lit = true;
      }
      return ipsvi_visibility(k, light, paper_albedo(k.scattering.blend, v.material.albedo, vec3(c)), p,
                              ray.direction, v.material.shading == Shading::Phase);
    };
    if (!k.piecewise) visibility();  // the run's write is made of the samples' light
    const float t_ray = forward ? t : tb - t;
    const bool go_on = shade(t_ray, SamplePoint{p, index, value, vec3(c), c.a, ray.direction}, grid.length(kk),
                             visibility);
    if (!st.recording() && k.cache.covers(vec2(proj))) add_to_run(k, vec2(proj), proj.z, light, st);
    if (!go_on) break;
  }
  flush_run(k, st);
}

// The colour and opacity of one viewing ray, as march_ray returns them.
// `exit_t`: with the ERT extension, the depth after which the cache needs no
// more samples once the colour has terminated (+inf without it). `tape`:
// record the light segments (nothing else is then written and the colour is
// meaningless) or replay them (segment_tape.h).
template <class Sampler>
PENUMBRA_HD vec4 trace_ipsvi_ray(const IpsviKernel& k, const Sampler& sampler, const Ray& ray, float offset,
                                 float exit_t, IpsviRayCounts& counts, SegmentTape* tape = nullptr) {
  const RenderView& v = *k.view;
  float t_plane = kInfinity;
  const int plane = nearest_plane(v, ray, kInfinity, t_plane);
  if (tape && !k.piecewise) tape = nullptr;  // recorded: piecewise integration's segments only
  const Interval iv = volume_interval(v, ray, 0.0f, t_plane);
  const float min_transmittance = 1.0f - v.ert_threshold;
  const float split = iv.empty() ? iv.t0 : glm::clamp(light_parameter(v.lights[0], ray), iv.t0, iv.t1);
  RayCacheState st;
  st.ray_direction = ray.direction;
  st.tape = tape;
  st.exit_t = exit_t;
  const bool recording = st.recording();  // only the light segments matter

  // The part beyond the light's closest approach, front to back, then what
  // lies behind it (a plane or the background).
  vec3 color(0.0f);
  float transmittance = 1.0f;
  bool terminated = false;
  ipsvi_march(k, sampler, ray, split, iv.t1, true, offset, st, counts,
              [&](float t, const SamplePoint& s, float length, auto&& visibility) {
                if (terminated) return t < exit_t;
                if (s.sigma_t > 0.0f) {
                  const float alpha = 1.0f - exp_nonpositive(-s.sigma_t * length);
                  const vec3 visible = visibility();
                  if (!recording) {
                    color += (transmittance * alpha) *
                             ScatteringLighting<FixedVisibility>{&v, {visible}, v.material.shading}.sample(s);
                  }
                  transmittance *= 1.0f - alpha;
                  terminated = transmittance <= min_transmittance;
                  st.colour_done = terminated;
                }
                return !terminated || t < exit_t;
              });
  float alpha_out = 1.0f - transmittance;
  if (!terminated) {
    if (plane >= 0 && recording) {
      alpha_out = 1.0f;  // its light is not recorded (plane_light)
    } else if (plane >= 0) {
      const vec3 q = ray.at(t_plane);
      const CachedLight light = plane_light(k, sampler, q, st, counts);
      const vec3 visibility = ipsvi_visibility(k, light, vec3(k.scattering.blend), q, ray.direction, false);
      color += transmittance *
               ScatteringLighting<FixedVisibility>{&v, {visibility}, v.material.shading}.plane(
                   PlaneHit{q, plane, ray.direction});
      alpha_out = 1.0f;
    } else {
      color += transmittance * v.background;
    }
  }

  // The part before it, back to front over what is behind.
  float front_transmittance = 1.0f;
  st.texel = -1;
  st.colour_done = false;  // before the light's closest approach every sample is shaded
  ipsvi_march(k, sampler, ray, iv.t0, split, false, offset, st, counts,
              [&](float, const SamplePoint& s, float length, auto&& visibility) {
                if (s.sigma_t > 0.0f) {
                  const float alpha = 1.0f - exp_nonpositive(-s.sigma_t * length);
                  const vec3 visible = visibility();
                  if (!recording) {
                    color = alpha * ScatteringLighting<FixedVisibility>{&v, {visible}, v.material.shading}.sample(s) +
                            (1.0f - alpha) * color;
                  }
                  front_transmittance *= 1.0f - alpha;
                }
                return true;
              });
  return vec4(color, 1.0f - front_transmittance * (1.0f - alpha_out));
}

}  // namespace penumbra

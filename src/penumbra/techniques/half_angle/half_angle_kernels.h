#pragma once
// The per-pixel and per-texel work of one slice in half-angle slicing (Kniss
// et al. 2002, 2003): where a viewing ray or a light ray crosses the slice
// plane it takes one sample; the eye buffer composites it lit by the light
// buffer, the light buffer is attenuated by it. The model is IPSVI's
// (techniques/ipsvi/forward_scattering.h): direct and diffuse light, the
// diffuse part attenuated by what leaves the cone and blurred per slice.
//
// Each kernel is written once over a lane type (base/lanes.h): the scalar
// path runs it on one pixel or texel, the SIMD units (half_angle_packets.cpp)
// on 8 or 16 consecutive ones of a buffer row, which is why the buffers the
// rows read are kept as structures of arrays (SlicedRows).
#include "penumbra/render/lighting.h"
#include "penumbra/render/march.h"
#include "penumbra/backends/cpu/packets.h"
#include "penumbra/techniques/half_angle/slice_geometry.h"
#include "penumbra/techniques/ipsvi/forward_scattering.h"
#include "penumbra/techniques/ipsvi/light_cache_projection.h"

#include <cstdint>

namespace penumbra {

// Rays (and, for the eye, pixels) of a buffer as a structure of arrays: field
// f of entry i at data[f * stride + i]. The owner pads each field by
// kSlicedRowPadding floats, so that a packet may load past a row's end; it
// never stores there.
inline constexpr int kSlicedRowPadding = 16;
struct SlicedRows {
  enum Field : int {
    kOriginX, kOriginY, kOriginZ, kDirectionX, kDirectionY, kDirectionZ,
    kLightFields,  // a light ray: the six above
    kTMax = kLightFields,  // viewing rays: the nearest opaque plane
    kRed, kGreen, kBlue,   // the eye pixel's colour
    // Front to back: what the colour still lets through; back to front: the
    // product of what has been composited over the base.
    kTransmittance,
    kEyeFields
  };
  float* data = nullptr;
  std::size_t stride = 0;
  PENUMBRA_HD float* field(int f) const { return data + std::size_t(f) * stride; }
};

// A viewing or light ray with its offsets along the slicing axis.
template <class L> struct SlicedRayL {
  typename L::Vec3 origin;
  typename L::Vec3 direction;
  typename L::Float origin_s;     // s . origin
  typename L::Float direction_s;  // s . direction
  typename L::Float t_max;        // viewing rays: the nearest opaque plane

  // The rays of entries [i, i + W) of `rows` (t_max only for viewing rays).
  PENUMBRA_HD static SlicedRayL load(const SlicedRows& rows, std::size_t i, vec3 axis, bool viewing) {
    using F = typename L::Float;
    using V = typename L::Vec3;
    SlicedRayL r;
    r.origin = V(L::load(rows.field(SlicedRows::kOriginX) + i), L::load(rows.field(SlicedRows::kOriginY) + i),
                 L::load(rows.field(SlicedRows::kOriginZ) + i));
    r.direction = V(L::load(rows.field(SlicedRows::kDirectionX) + i), L::load(rows.field(SlicedRows::kDirectionY) + i),
                    L::load(rows.field(SlicedRows::kDirectionZ) + i));
    r.origin_s = dot(V(axis), r.origin);
    r.direction_s = dot(V(axis), r.direction);
    r.t_max = viewing ? L::load(rows.field(SlicedRows::kTMax) + i) : F(kInfinity);
    return r;
  }

  // The ray parameter where it crosses the slice at `position` (or -1).
  PENUMBRA_HD typename L::Float crossing(float position) const {
    using F = typename L::Float;
    return select(max(direction_s, -direction_s) > 1e-6f, (position - origin_s) / direction_s, F(-1.0f));
  }
};

// An eye-buffer pixel (SlicedRows' colour and transmittance).
template <class L> struct EyePixelL {
  typename L::Vec3 color;
  typename L::Float transmittance;
};

// What a slice leaves of a light-buffer texel: the factors of its direct and
// diffuse parts.
template <class L> struct TexelAttenuationL {
  typename L::Float direct;
  typename L::Vec3 diffuse;
};

struct HalfAngleKernel {
  const RenderView* view = nullptr;    // lights[0] is the light of this pass
  const RenderView* shadow = nullptr;  // with the shadow TF: what attenuates light
  bool separate_shadow_tf = false;
  SliceSetup slices;
  LightCacheProjection projection;  // the light buffer's mapping
  const vec4* light = nullptr;      // light buffer: (direct, diffuse rgb) per texel
  ForwardScattering scattering;

  // Bilinear light-buffer read at texel coordinates (u, v) of the lanes in
  // `active`; outside the buffer nothing shadows.
  template <class L>
  PENUMBRA_HD PENUMBRA_FORCE_INLINE TexelAttenuationL<L> read_light(typename L::Float u, typename L::Float v,
                                                                    typename L::Mask active) const {
    using F = typename L::Float;
    using I = typename L::Int;
    using V = typename L::Vec3;
    const int n = projection.size;
    const auto covered = active & (u >= 0.0f) & (v >= 0.0f) & (u <= float(n)) & (v <= float(n));
    if (none(covered)) return {F(1.0f), V(1.0f)};
    const F x = select(covered, clamp(u - 0.5f, F(0.0f), F(float(n - 1))), F(0.0f));
    const F y = select(covered, clamp(v - 0.5f, F(0.0f), F(float(n - 1))), F(0.0f));
    const I x0 = to_int_nonnegative(x), y0 = to_int_nonnegative(y);
    const I x1 = min(x0 + 1, I(n - 1)), y1 = min(y0 + 1, I(n - 1));
    const F fx = x - to_float(x0), fy = y - to_float(y0);
    const float* texels = &light[0].x;
    F c[4][4];
    const I corners[4] = {x0 + n * y0, x1 + n * y0, x0 + n * y1, x1 + n * y1};
    for (int j = 0; j < 4; ++j) gather4(texels, typename L::Index(corners[j] * 4), c[j][0], c[j][1], c[j][2], c[j][3]);
    // glm::mix(a, b, t) = a (1 - t) + b t, per channel.
    F mixed[4];
    for (int q = 0; q < 4; ++q) {
      const F lower = c[0][q] * (1.0f - fx) + c[1][q] * fx;
      const F upper = c[2][q] * (1.0f - fx) + c[3][q] * fx;
      mixed[q] = select(covered, lower * (1.0f - fy) + upper * fy, F(1.0f));
    }
    return {mixed[0], V(mixed[1], mixed[2], mixed[3])};
  }

  // Distance along the light ray through p between two slices (<= 0: the
  // light does not advance with the slices there).
  template <class L> PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Float light_step(const typename L::Vec3& p) const {
    using F = typename L::Float;
    using V = typename L::Vec3;
    const Light& l = view->lights[0];
    const V w = l.at_infinity() ? V(glm::normalize(l.direction)) : -sample_light<L>(l, p).to_light;
    const F c = dot(w, V(slices.axis));
    return select(c > 1e-4f, slices.spacing / c, F(-1.0f));
  }

  // Light visibility at p: the buffer as the slices before this one left it,
  // attenuated over half a slab by the medium at p (extinction sigma, shadow
  // TF colour) so that a sample sees the light at its own depth.
  template <class L>
  PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Vec3 visibility(const typename L::Vec3& p, typename L::Float sigma,
                                                                const typename L::Vec3& color,
                                                                typename L::Mask active) const {
    using F = typename L::Float;
    using V = typename L::Vec3;
    const V proj = projection.project<L>(p);
    TexelAttenuationL<L> l = read_light<L>(proj.x, proj.y, active);
    const F half = 0.5f * light_step<L>(p);
    const auto absorbs = (half > 0.0f) & (sigma > 0.0f);
    if (any(absorbs)) {
      l.direct = select(absorbs, l.direct * exp_nonpositive(-sigma * half), l.direct);
      if (scattering.has_diffuse()) {
        const V tau = scattering.diffuse_extinction<L>(color, sigma) * half;
        l.diffuse = select(
            absorbs, l.diffuse * V(exp_nonpositive(-tau.x), exp_nonpositive(-tau.y), exp_nonpositive(-tau.z)),
            l.diffuse);
      }
    }
    return scattering.visibility<L>(l.direct, l.diffuse);
  }
  PENUMBRA_HD vec3 visibility(vec3 p, float sigma, vec3 color) const {
    return visibility<ScalarLanes>(p, sigma, color, true);
  }

  template <class L> PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Mask inside(const typename L::Vec3& p) const {
    return box_contains<L>(view->box, p) & inside_clip_planes<L>(p, view->clip_planes, view->clip_plane_count);
  }

  // The lanes of `active` whose ray reaches slice `slice` at a point of the
  // box (clip planes kept) in a macrocell that can hold extinction under
  // `v`'s TF: its world and index-space position (0 in the other lanes).
  template <class L>
  PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Mask slice_point(const RenderView& v, const SlicedRayL<L>& ray,
                                                                 int slice, typename L::Mask active,
                                                                 typename L::Vec3& p, typename L::Vec3& index) const {
    using V = typename L::Vec3;
    const typename L::Float t = ray.crossing(slices.position(slice));
    active = active & (t > 0.0f) & (t < ray.t_max);
    if (none(active)) return active;
    p = ray.origin + t * ray.direction;
    active = active & inside<L>(p);
    if (none(active)) return active;
    index = select(active, v.volume.index_from_world<L>(p), V(0.0f));
    return active & (v.majorant_at<L>(index) > 0.0f);
  }
};

// The sample of slice `slice` on the viewing rays of the lanes in `active`,
// composited into their pixels.
template <class L, class Sampler>
PENUMBRA_HD PENUMBRA_FORCE_INLINE void eye_slice_sample(const HalfAngleKernel& k, const Sampler& sampler,
                                                        const SlicedRayL<L>& ray, int slice, typename L::Mask active,
                                                        EyePixelL<L>& px, std::uint64_t& samples) {
  using F = typename L::Float;
  using V = typename L::Vec3;
  using M = typename L::Mask;
  const RenderView& v = *k.view;
  if (k.slices.eye_front_to_back) active = active & (px.transmittance > 1.0f - v.ert_threshold);
  // A ray crossing the slices against the compositing order cannot be
  // composited by them (only at extreme fields of view).
  active = active & ((ray.direction_s > 0.0f) == M(k.slices.eye_front_to_back));
  if (none(active)) return;
  V p, index;
  active = k.slice_point<L>(v, ray, slice, active, p, index);
  if (none(active)) return;
  samples += std::uint64_t(count_true(active));
  const F value = sampler.template sample<L>(index);
  typename TransferFunctionView::Place<L> at;
  const F sigma = sample_extinction<L>(v.tf, sampler, value, at);
  active = active & (sigma > 0.0f);
  if (none(active)) return;
  const V color = v.tf.color<L>(at);
  F shadow_sigma = sigma;
  V shadow_color = color;
  if (k.separate_shadow_tf) {
    typename TransferFunctionView::Place<L> shadow_at;
    shadow_sigma = sample_extinction<L>(k.shadow->tf, sampler, value, shadow_at);
    shadow_color = k.shadow->tf.color<L>(shadow_at);
  }
  const F alpha = 1.0f - exp_nonpositive(-sigma * k.slices.spacing / max(ray.direction_s, -ray.direction_s));
  const V visibility = k.visibility<L>(p, shadow_sigma, shadow_color, active);
  const V lit = ScatteringLighting<FixedVisibilityL<L>>{&v, {visibility}, v.material.shading}.template sample<L>(
      SamplePointL<L>{p, index, value, color, sigma, ray.direction}, active);
  if (k.slices.eye_front_to_back) {
    px.color = select(active, px.color + (px.transmittance * alpha) * lit, px.color);
  } else {
    px.color = select(active, alpha * lit + (1.0f - alpha) * px.color, px.color);
  }
  px.transmittance = select(active, px.transmittance * (1.0f - alpha), px.transmittance);
}

// What slice `slice` leaves of the light-buffer texels whose light rays are
// `ray` (the lanes in `active`).
template <class L, class Sampler>
PENUMBRA_HD PENUMBRA_FORCE_INLINE TexelAttenuationL<L> light_slice_sample(const HalfAngleKernel& k,
                                                                          const Sampler& sampler,
                                                                          const SlicedRayL<L>& ray, int slice,
                                                                          typename L::Mask active,
                                                                          std::uint64_t& samples) {
  using F = typename L::Float;
  using V = typename L::Vec3;
  TexelAttenuationL<L> out{F(1.0f), V(1.0f)};
  const RenderView& v = *k.shadow;
  active = active & (ray.direction_s > 1e-4f);
  if (none(active)) return out;
  V p, index;
  active = k.slice_point<L>(v, ray, slice, active, p, index);
  if (none(active)) return out;
  samples += std::uint64_t(count_true(active));
  typename TransferFunctionView::Place<L> at;
  const F sigma = sample_extinction<L>(v.tf, sampler, sampler.template sample<L>(index), at);
  active = active & (sigma > 0.0f);
  if (none(active)) return out;
  const F length = k.slices.spacing / ray.direction_s;
  out.direct = select(active, exp_nonpositive(-sigma * length), F(1.0f));
  if (k.scattering.has_diffuse()) {
    const V tau = k.scattering.diffuse_extinction<L>(v.tf.color<L>(at), sigma) * length;
    out.diffuse = select(active, V(exp_nonpositive(-tau.x), exp_nonpositive(-tau.y), exp_nonpositive(-tau.z)), V(1.0f));
  }
  return out;
}

// Slice `slice` for the eye pixels [first, first + count) of `eye`
// (consecutive, one buffer row), W at a time.
template <class L, class Sampler>
PENUMBRA_HD void eye_slice_row(const HalfAngleKernel& k, const Sampler& sampler, const SlicedRows& eye, int slice,
                               std::size_t first, int count, std::uint64_t& samples) {
  using V = typename L::Vec3;
  float* red = eye.field(SlicedRows::kRed);
  float* green = eye.field(SlicedRows::kGreen);
  float* blue = eye.field(SlicedRows::kBlue);
  float* transmittance = eye.field(SlicedRows::kTransmittance);
  for (int x = 0; x < count; x += L::kWidth) {
    const std::size_t i = first + std::size_t(x);
    const int n = count - x;
    const SlicedRayL<L> ray = SlicedRayL<L>::load(eye, i, k.slices.axis, true);
    EyePixelL<L> px{V(L::load(red + i), L::load(green + i), L::load(blue + i)), L::load(transmittance + i)};
    const typename L::Float before = px.transmittance;
    eye_slice_sample<L>(k, sampler, ray, slice, first_lanes<L>(n), px, samples);
    if (none(px.transmittance != before)) continue;  // no lane composited a sample
    store_first<L>(px.color.x, red + i, n);
    store_first<L>(px.color.y, green + i, n);
    store_first<L>(px.color.z, blue + i, n);
    store_first<L>(px.transmittance, transmittance + i, n);
  }
}

// Slice `slice` attenuating the light-buffer texels [first, first + count)
// (one buffer row; their light rays in `rays`), W at a time.
template <class L, class Sampler>
PENUMBRA_HD void light_slice_row(const HalfAngleKernel& k, const Sampler& sampler, const SlicedRows& rays, int slice,
                                 std::size_t first, int count, vec4* texels, std::uint64_t& samples) {
  for (int x = 0; x < count; x += L::kWidth) {
    const std::size_t i = first + std::size_t(x);
    const int n = count - x;
    const SlicedRayL<L> ray = SlicedRayL<L>::load(rays, i, k.slices.axis, false);
    const TexelAttenuationL<L> a = light_slice_sample<L>(k, sampler, ray, slice, first_lanes<L>(n), samples);
    if (all(a.direct == 1.0f) && all((a.diffuse.x == 1.0f) & (a.diffuse.y == 1.0f) & (a.diffuse.z == 1.0f))) {
      continue;  // nothing attenuated (multiplying by 1 would change no texel)
    }
    if constexpr (L::kWidth == 1) {
      texels[i] *= vec4(a.direct, a.diffuse);
    } else {
      float f[4][L::kWidth];
      L::store(a.direct, f[0]), L::store(a.diffuse.x, f[1]), L::store(a.diffuse.y, f[2]), L::store(a.diffuse.z, f[3]);
      for (int j = 0; j < n && j < L::kWidth; ++j) {
        texels[i + std::size_t(j)] *= vec4(f[0][j], f[1][j], f[2][j], f[3][j]);
      }
    }
  }
}

// The rows as packets of Target (AnyVoxelSampler over the view's volume);
// defined only in the SIMD units of Target (half_angle_packets.cpp). Return
// the samples taken.
template <SimdTarget Target>
std::uint64_t eye_slice_row_packets(const HalfAngleKernel& k, const SlicedRows& eye, int slice, std::size_t first,
                                    int count);
template <SimdTarget Target>
std::uint64_t light_slice_row_packets(const HalfAngleKernel& k, const SlicedRows& rays, int slice, std::size_t first,
                                      int count, vec4* texels);

}  // namespace penumbra

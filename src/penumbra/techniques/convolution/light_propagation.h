#pragma once
// Step (1) of Patel et al. 2013, section 4.2: the light arriving at slab k is
// the light that left slab k - 1, convolved with the slab kernel. Light
// buffers live on the image's pixel grid (one texel per pixel, as the paper's
// screen-space buffers); texel i of slab k is the point where pixel i's
// viewing ray crosses the slab's plane at depth z_k (depth along the camera's
// forward axis f). The light reaching that point P came from
//   Q = P - e f - (offset_j . (r, u)),   offset_j = a kernel tap (mean e mu),
// on slab k - 1, which is projected back into that slab's pixel grid and read
// bilinearly. Doing the step in world space keeps perspective cameras right:
// their pixel rays diverge, so a light along f drifts across pixels.
// Outside the image the previous buffer is clamped to its edge texels (as a
// GPU texture with clamp-to-edge): light entering from outside the view has
// crossed what the border pixels saw, the closest guess available.
#include "penumbra/backends/cpu/packets.h"
#include "penumbra/base/lanes.h"
#include "penumbra/render/image.h"
#include "penumbra/scene/camera.h"
#include "penumbra/techniques/convolution/slab_kernel.h"

namespace penumbra {

struct SlabFrame {
  CameraView camera;
  int width = 0, height = 0;
  float slab_distance = 1.0f;  // e, world units
};

// The world point at `depth` (along the camera's forward axis) on the
// viewing ray through frame pixel coordinates p (pixel centres at +0.5).
PENUMBRA_HD inline vec3 slab_point(const SlabFrame& f, vec2 p, float depth) {
  const Ray ray = f.camera.pixel_ray(p.x, p.y, f.width, f.height);
  return ray.origin + ray.direction * (depth / glm::dot(ray.direction, f.camera.forward));
}
// The same at pixel (x, y)'s centre.
PENUMBRA_HD inline vec3 slab_point(const SlabFrame& f, int x, int y, float depth) {
  return slab_point(f, vec2(float(x) + 0.5f, float(y) + 0.5f), depth);
}

// Continuous pixel coordinates (texel centres at +0.5) of a world point.
PENUMBRA_HD inline vec2 pixel_of(const SlabFrame& f, vec3 q) {
  const CameraView& c = f.camera;
  const vec3 d = q - c.eye;
  float sx = glm::dot(d, c.right), sy = glm::dot(d, c.up);
  if (!c.orthographic) {
    const float z = glm::max(glm::dot(d, c.forward), 1e-6f);
    sx /= z;
    sy /= z;
  }
  const float aspect = float(f.width) / float(f.height);
  return vec2((sx / (c.half_height * aspect) + 1.0f) * 0.5f * float(f.width),
              (1.0f - sy / c.half_height) * 0.5f * float(f.height));
}

// Bilinear read of a buffer at pixel coordinates (px, py), clamped to the
// edge texels, over a lane type whose lanes share the row py (a slab's row
// maps to one row of the previous slab: slab_mapping); read_buffer is its
// one-lane instance.
template <class L>
PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Float read_buffer_row(const float* buffer, int width, int height,
                                                                    typename L::Float px, float py) {
  using F = typename L::Float;
  using I = typename L::Int;
  using X = typename L::Index;
  const F fx = px - 0.5f;
  const float fy = py - 0.5f;
  const F x0f = floor(fx);
  const float y0f = glm::floor(fy);
  const F tx = fx - x0f;
  const float ty = fy - y0f;
  const I x0 = to_int(x0f);
  const int y0 = int(y0f);
  const I xa = max(I(0), min(x0, I(width - 1))), xb = max(I(0), min(x0 + I(1), I(width - 1)));
  const I ra(width * glm::clamp(y0, 0, height - 1)), rb(width * glm::clamp(y0 + 1, 0, height - 1));
  const F a = gather(buffer, X(ra + xa)), b = gather(buffer, X(ra + xb));
  const F c = gather(buffer, X(rb + xa)), d = gather(buffer, X(rb + xb));
  return (1.0f - ty) * ((1.0f - tx) * a + tx * b) + ty * ((1.0f - tx) * c + tx * d);
}

PENUMBRA_HD inline float read_buffer(const float* buffer, int width, int height, vec2 p) {
  return read_buffer_row<ScalarLanes>(buffer, width, height, p.x, p.y);
}

// A sharper read for single-tap kernels (zero-variance lights), where the
// slab-to-slab re-sampling is the only blur: Catmull-Rom bicubic
// interpolation reproduces quadratics, so unlike bilinear reads (which add a
// variance of f (1 - f) texels^2 per axis and step, f the fractional offset)
// it adds no second moment, and a hard shadow stays hard over hundreds of
// slabs. Clamped to the four nearest texels' range so its negative lobes
// cannot ring (light stays within [0, 1] of the light's colour).
PENUMBRA_HD inline void catmull_rom_weights(float t, float w[4]) {
  const float t2 = t * t, t3 = t2 * t;
  w[0] = 0.5f * (-t3 + 2.0f * t2 - t);
  w[1] = 0.5f * (3.0f * t3 - 5.0f * t2 + 2.0f);
  w[2] = 0.5f * (-3.0f * t3 + 4.0f * t2 + t);
  w[3] = 0.5f * (t3 - t2);
}

PENUMBRA_HD inline float read_buffer_sharp(const float* buffer, int width, int height, vec2 p) {
  const float fx = p.x - 0.5f, fy = p.y - 0.5f;
  const float x0f = glm::floor(fx), y0f = glm::floor(fy);
  const int x0 = int(x0f), y0 = int(y0f);
  float wx[4], wy[4];
  catmull_rom_weights(fx - x0f, wx);
  catmull_rom_weights(fy - y0f, wy);
  auto at = [&](int x, int y) { return buffer[glm::clamp(x, 0, width - 1) + width * glm::clamp(y, 0, height - 1)]; };
  float sum = 0.0f;
  for (int j = 0; j < 4; ++j) {
    float row = 0.0f;
    for (int i = 0; i < 4; ++i) row += wx[i] * at(x0 - 1 + i, y0 - 1 + j);
    sum += wy[j] * row;
  }
  const float a = at(x0, y0), b = at(x0 + 1, y0), c = at(x0, y0 + 1), d = at(x0 + 1, y0 + 1);
  return glm::clamp(sum, glm::min(glm::min(a, b), glm::min(c, d)), glm::max(glm::max(a, b), glm::max(c, d)));
}

// The convolved light arriving at texel (x, y) of the slab at `depth`.
PENUMBRA_HD inline float convolve_texel(const SlabFrame& f, const SlabKernel& k, const float* previous, int x, int y,
                                       float depth) {
  const vec3 p = slab_point(f, x, y, depth) - f.slab_distance * f.camera.forward;
  const float phi = k.pixel_angle(x, y);
  const float c = glm::cos(phi), s = glm::sin(phi);
  float sum = 0.0f;
  for (int j = 0; j < k.count; ++j) {
    const vec2 o = k.offset(j, c, s);
    const vec3 q = p - o.x * f.camera.right - o.y * f.camera.up;
    sum += k.weights[j] * read_buffer(previous, f.width, f.height, pixel_of(f, q));
  }
  return sum;
}

// The same map from slab k's texels to slab k - 1's pixel coordinates in
// closed form: the pinhole projection makes it affine. With s = z / (z - e)
// (1 for an orthographic camera) and k = H / (2 h (z - e)) pixels per world
// unit of lateral offset at depth z - e (H / (2 h) orthographic; h the
// camera's half_height), a texel centre p and a tap offset o map to
//   p' = c + s (p - c) + k (-o.x, o.y),   c = the image centre (W/2, H/2).
struct SlabMapping {
  vec2 center{0.0f};
  float scale = 1.0f;
  float pixels_per_unit = 1.0f;
};

PENUMBRA_HD inline SlabMapping slab_mapping(const SlabFrame& f, float depth) {
  SlabMapping m;
  m.center = vec2(0.5f * float(f.width), 0.5f * float(f.height));
  const float source_depth = glm::max(depth - f.slab_distance, 1e-6f);
  if (f.camera.orthographic) {
    m.pixels_per_unit = float(f.height) / (2.0f * f.camera.half_height);
  } else {
    m.scale = depth / source_depth;
    m.pixels_per_unit = float(f.height) / (2.0f * f.camera.half_height * source_depth);
  }
  return m;
}

// convolve_texel through the affine map (what convolve_slab runs).
PENUMBRA_HD inline float convolve_texel_mapped(const SlabFrame& f, const SlabMapping& m, const SlabKernel& k,
                                               const float* previous, int x, int y) {
  const vec2 p = m.center + m.scale * (vec2(float(x) + 0.5f, float(y) + 0.5f) - m.center);
  float c = 1.0f, s = 0.0f;
  if (k.rotate_per_pixel) {
    const float phi = k.pixel_angle(x, y);
    c = glm::cos(phi);
    s = glm::sin(phi);
  }
  if (k.count == 1) {
    const vec2 o = k.offset(0, c, s);
    return read_buffer_sharp(previous, f.width, f.height, p + m.pixels_per_unit * vec2(-o.x, o.y));
  }
  float sum = 0.0f;
  for (int j = 0; j < k.count; ++j) {
    const vec2 o = k.offset(j, c, s);
    sum += k.weights[j] * read_buffer(previous, f.width, f.height, p + m.pixels_per_unit * vec2(-o.x, o.y));
  }
  return sum;
}

// Bilinear reads blur too: a read at fractional offset f is a two-tap kernel
// (1 - f, f) of variance f (1 - f) texels^2 per axis, added every slab, so an
// uncorrected penumbra is wider the coarser the image (issue 23: 5.8 / 6.7 /
// 9.9 units at 256^2 / 128^2 / 64^2 for an analytic 5.47). The kernel's
// covariance that, with its own taps' interpolation variance (averaged over
// slabs and per-pixel rotations, at `pixels_per_unit` texels per world unit
// of lateral offset) added, gives `covariance`. Exact for orthographic
// cameras, whose texel-to-texel map is a pure shift; for perspective ones it
// uses the scale at the depth passed in. Each principal variance keeps at
// least a tenth of its value (a kernel narrower than the interpolation cannot
// be corrected further; zero-variance lights are read sharp and need none).
glm::mat2 interpolation_corrected_covariance(SlabKernelType type, int samples, vec2 mean, const glm::mat2& covariance,
                                             std::uint64_t seed, float pixels_per_unit);

// Row y of convolve_texel_mapped for a kernel of several taps the same at
// every pixel (no per-pixel rotation), L::kWidth texels at a time, into
// `incoming` (the row's first texel).
template <class L>
PENUMBRA_HD void convolve_row(const SlabFrame& f, const SlabMapping& m, const SlabKernel& k, const float* previous,
                              int y, float* incoming) {
  using F = typename L::Float;
  constexpr int W = L::kWidth;
  static constexpr float kCentres[16] = {0.5f, 1.5f, 2.5f,  3.5f,  4.5f,  5.5f,  6.5f,  7.5f,
                                         8.5f, 9.5f, 10.5f, 11.5f, 12.5f, 13.5f, 14.5f, 15.5f};
  static_assert(W <= 16, "pixel centres for up to 16 lanes");
  const float py = m.center.y + m.scale * ((float(y) + 0.5f) - m.center.y);
  for (int x = 0; x < f.width; x += W) {
    const F px = m.center.x + m.scale * ((F(float(x)) + L::load(kCentres)) - m.center.x);
    F sum(0.0f);
    for (int j = 0; j < k.count; ++j) {
      const vec2 o = k.taps[j];
      sum = sum + k.weights[j] * read_buffer_row<L>(previous, f.width, f.height, px + m.pixels_per_unit * (-o.x),
                                                    py + m.pixels_per_unit * o.y);
    }
    store_first<L>(sum, incoming + x, f.width - x);
  }
}

// The row as packets of Target. Defined only in the SIMD units of Target
// (convolution_packets.cpp).
template <SimdTarget Target>
void convolve_row_packets(const SlabFrame& f, const SlabMapping& m, const SlabKernel& k, const float* previous, int y,
                          float* incoming);
using ConvolveRow = void (*)(const SlabFrame&, const SlabMapping&, const SlabKernel&, const float*, int, float*);
// The packet row convolve_slab takes for `kernel` on a frame of `pixels`
// (several taps, no per-pixel rotation, the active target's SIMD unit), or
// nullptr.
ConvolveRow convolve_row_function(const SlabKernel& kernel, std::size_t pixels);

// The whole buffer for the slab at `depth` (parallel over rows): slab k's
// incoming light from slab k - 1's (`previous`). Kernels of several taps
// without per-pixel rotation run by rows (convolve_row, as packets where the
// build has them); the rotated Poisson kernel and single taps per texel
// (convolve_texel_mapped).
void convolve_slab(const SlabFrame& frame, const SlabKernel& kernel, const float* previous, float* incoming,
                   float depth);
// The same through a given map (a point light's, slab_renderer.cpp).
void convolve_slab(const SlabFrame& frame, const SlabMapping& mapping, const SlabKernel& kernel, const float* previous,
                   float* incoming);

}  // namespace penumbra

#include "penumbra/techniques/convolution/light_propagation.h"

#include "penumbra/base/parallel.h"
#include "penumbra/techniques/convolution/gaussian_light.h"

#include <cmath>

namespace penumbra {
namespace {

double interpolation_variance_1d(double texels) {
  const double f = texels - std::floor(texels);
  return f * (1.0 - f);
}

// Mean per-axis variance (world units^2) the bilinear reads add to a slab
// step with this kernel: over 8 slabs and, for per-pixel rotations, 16 angles.
glm::dvec2 interpolation_variance(SlabKernelBuilder& builder, float pixels_per_unit) {
  constexpr int kSlabs = 8, kAngles = 16;
  glm::dvec2 sum(0.0);
  int count = 0;
  for (int slab = 1; slab <= kSlabs; ++slab) {
    const SlabKernel k = builder.for_slab(slab);
    if (k.count == 1) return glm::dvec2(0.0);  // read with Catmull-Rom: no added variance
    const int angles = k.rotate_per_pixel ? kAngles : 1;
    for (int a = 0; a < angles; ++a) {
      const double phi = 6.283185307179586 * (double(a) + 0.5 * double(slab % 2)) / double(angles);
      const float c = float(std::cos(phi)), s = float(std::sin(phi));
      for (int j = 0; j < k.count; ++j) {
        const vec2 o = k.offset(j, c, s);
        sum.x += double(k.weights[j]) * interpolation_variance_1d(-double(o.x) * pixels_per_unit);
        sum.y += double(k.weights[j]) * interpolation_variance_1d(double(o.y) * pixels_per_unit);
      }
      ++count;
    }
  }
  return sum / (double(count) * double(pixels_per_unit) * double(pixels_per_unit));
}

glm::mat2 from_axes(float var_x, float var_y, float angle) {
  const glm::mat2 r(std::cos(angle), std::sin(angle), -std::sin(angle), std::cos(angle));
  return r * glm::mat2(var_x, 0.0f, 0.0f, var_y) * glm::transpose(r);
}

}  // namespace

glm::mat2 interpolation_corrected_covariance(SlabKernelType type, int samples, vec2 mean, const glm::mat2& covariance,
                                             std::uint64_t seed, float pixels_per_unit) {
  const PrincipalAxes target = principal_axes(covariance);
  if (!(pixels_per_unit > 0.0f) || (target.var_x <= 0.0f && target.var_y <= 0.0f)) return covariance;
  glm::mat2 kernel = covariance;
  for (int iteration = 0; iteration < 8; ++iteration) {
    SlabKernelBuilder builder(type, samples, mean, kernel, seed);
    const glm::dvec2 v = interpolation_variance(builder, pixels_per_unit);
    const PrincipalAxes axes = principal_axes(covariance - glm::mat2(float(v.x), 0.0f, 0.0f, float(v.y)));
    // principal_axes sorts var_x >= var_y, for the target as for this.
    const glm::mat2 wanted = from_axes(glm::max(axes.var_x, 0.1f * target.var_x),
                                       glm::max(axes.var_y, 0.1f * target.var_y), axes.angle);
    // Damped after the first steps: the taps' fractional offsets move with
    // the kernel, so a narrow kernel's correction can oscillate.
    kernel = iteration < 2 ? wanted : 0.5f * (wanted + kernel);
  }
  return kernel;
}

ConvolveRow convolve_row_function(const SlabKernel& kernel, std::size_t pixels) {
  // Packets need 32-bit gather offsets into the buffer.
  if (kernel.count <= 1 || kernel.rotate_per_pixel || pixels >= (std::size_t(1) << 31)) return nullptr;
  return simd_unit_function(active_simd_target(), []<SimdTarget T>() { return &convolve_row_packets<T>; });
}

void convolve_slab(const SlabFrame& frame, const SlabKernel& kernel, const float* previous, float* incoming,
                   float depth) {
  convolve_slab(frame, slab_mapping(frame, depth), kernel, previous, incoming);
}

void convolve_slab(const SlabFrame& frame, const SlabMapping& mapping, const SlabKernel& kernel, const float* previous,
                   float* incoming) {
  const bool rows = kernel.count > 1 && !kernel.rotate_per_pixel;
  const ConvolveRow packets = convolve_row_function(kernel, std::size_t(frame.width) * std::size_t(frame.height));
  parallel_for(0, frame.height, [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t y = first; y < last; ++y) {
      float* row = incoming + std::size_t(frame.width) * std::size_t(y);
      if (packets) {
        packets(frame, mapping, kernel, previous, int(y), row);
        continue;
      }
      if (rows) {
        convolve_row<ScalarLanes>(frame, mapping, kernel, previous, int(y), row);
        continue;
      }
      for (int x = 0; x < frame.width; ++x) {
        incoming[x + frame.width * int(y)] = convolve_texel_mapped(frame, mapping, kernel, previous, x, int(y));
      }
    }
  });
}

}  // namespace penumbra

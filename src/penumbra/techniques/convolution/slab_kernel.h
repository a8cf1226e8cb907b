#pragma once
// One slab's 2D convolution kernel as plain taps (Patel et al. 2013, section
// 3.4), and the host object that builds it per slab for one light:
//   gaussian  an explicit M x M grid (M = kernel_samples, odd; the paper's
//             19 x 19) along the covariance's principal axes, Gaussian weights
//             truncated at 3 sigma, positions rescaled so the discrete kernel
//             has exactly the requested variances;
//   poisson   N points of a fixed Poisson-disk pattern (dart throwing), centred
//             and scaled to unit variance per axis under rotation, rotated by a
//             random angle per pixel and slab (Isidoro 2006) and mapped by
//             R(alpha) diag(sigma_x, sigma_y);
//   ellipse   N points equidistant in arc length on the ellipse whose
//             arc-length density has the requested variances
//             (ellipse_tables.h), with a random offset along the circumference
//             per slab (default N = 2).
// All taps are lateral world offsets (camera right, up) and include the mean.
#include "penumbra/base/math.h"
#include "penumbra/base/rng.h"

#include <glm/mat2x2.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace penumbra {

enum class SlabKernelType { Gaussian, Poisson, Ellipse };

SlabKernelType parse_slab_kernel(const std::string& name);  // throws InvalidArgument("kernel")

struct SlabKernel {
  const vec2* taps = nullptr;  // world offsets; unit pattern when rotate_per_pixel
  const float* weights = nullptr;
  int count = 0;
  bool rotate_per_pixel = false;
  vec2 axis_x{0.0f}, axis_y{0.0f};  // maps the unit pattern when rotate_per_pixel
  vec2 mean{0.0f};
  std::uint64_t seed = 0;  // per slab and light

  // Offset of tap j for the pixel (x, y).
  PENUMBRA_HD vec2 offset(int j, float cos_phi, float sin_phi) const {
    if (!rotate_per_pixel) return taps[j];
    const vec2 u = taps[j];
    const vec2 r(cos_phi * u.x - sin_phi * u.y, sin_phi * u.x + cos_phi * u.y);
    return mean + r.x * axis_x + r.y * axis_y;
  }

  PENUMBRA_HD float pixel_angle(int x, int y) const {
    if (!rotate_per_pixel) return 0.0f;
    const std::uint64_t h = mix_bits(seed ^ (std::uint64_t(std::uint32_t(x)) << 32 | std::uint32_t(y)));
    return float(h >> 40) * (6.28318530718f / 16777216.0f);
  }
};

class SlabKernelBuilder {
 public:
  // mean and covariance in world units (e mu and d1 e Sigma); samples <= 0
  // picks the kernel's default (gaussian 19, poisson 8, ellipse 2).
  SlabKernelBuilder(SlabKernelType type, int samples, vec2 mean, const glm::mat2& covariance, std::uint64_t seed);

  SlabKernel for_slab(int slab);
  int sample_count() const { return int(weights_.size()); }

 private:
  SlabKernelType type_;
  vec2 mean_;
  std::uint64_t seed_;
  vec2 axis_x_{0.0f}, axis_y_{0.0f};  // principal axes scaled by the std deviations
  float angle_ = 0.0f;
  glm::dvec2 radii_{0.0};             // ellipse
  std::vector<double> arc_;           // ellipse: cumulative arc length over the angle grid
  std::vector<vec2> unit_, taps_;
  std::vector<float> weights_;
};

}  // namespace penumbra

#include "penumbra/techniques/occlusion_map/moment_pyramid.h"

#include "penumbra/base/error.h"
#include "penumbra/base/memory_budget.h"
#include "penumbra/base/parallel.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace penumbra {
namespace {

// out[o][j][i] = sum_t w_t in[o][first_j + t][i]: one axis of a grid seen as
// `outer` blocks of n_in lines of `inner` floats.
void resample_axis(const float* in, float* out, std::int64_t outer, std::int64_t inner, const ResamplingTaps& taps) {
  const std::int64_t n_in = taps.n_in, n_out = taps.n_out;
  parallel_for(0, outer * n_out, [&](std::int64_t first_item, std::int64_t last_item) {
    for (std::int64_t item = first_item; item < last_item; ++item) {
      const std::int64_t o = item / n_out, j = item % n_out;
      float* dst = out + (o * n_out + j) * inner;
      std::fill(dst, dst + inner, 0.0f);
      const int count = taps.count(int(j));
      for (int t = 0; t < count; ++t) {
        const float w = taps.weights[std::size_t(taps.begin[std::size_t(j)] + t)];
        const float* src = in + (o * n_in + taps.first[std::size_t(j)] + t) * inner;
        for (std::int64_t i = 0; i < inner; ++i) dst[i] += w * src[i];
      }
    }
  }, std::max<std::int64_t>(1, 65536 / std::max<std::int64_t>(inner, 1)));
}

// u of row r (y = r % dims.y, z = r / dims.y) of the voxels. Voxels cut away
// by a clip plane count as u = 0, like air, so clipped material occludes
// nothing; so do non-finite ones.
template <class T>
void normalised_row(const VolumeView& volume, vec2 range, const std::vector<vec4>& clip_planes, std::int64_t r,
                    std::vector<float>& u) {
  const T* row = static_cast<const T*>(volume.data) + r * volume.dims.x;
  const double scale = range.y > range.x ? 1.0 / (double(range.y) - double(range.x)) : 1.0;
  const float y = float(r % volume.dims.y), z = float(r / volume.dims.y);
  for (int x = 0; x < volume.dims.x; ++x) {
    const double v = double(row[x]);
    const bool clipped = !clip_planes.empty() &&
                         !inside_clip_planes(volume.world_from_index(vec3(float(x), y, z)), clip_planes.data(),
                                             int(clip_planes.size()));
    u[std::size_t(x)] = std::isfinite(v) && !clipped ? float(std::clamp((v - double(range.x)) * scale, 0.0, 1.0)) : 0.0f;
  }
}

// The first pass: voxels -> moments of u, resampled along x.
template <class T>
void moments_along_x(const VolumeView& volume, vec2 range, const std::vector<vec4>& clip_planes, int moments,
                     const ResamplingTaps& taps, float* out) {
  const std::int64_t rows = std::int64_t(volume.dims.y) * volume.dims.z;
  parallel_for(0, rows, [&](std::int64_t first_row, std::int64_t last_row) {
    std::vector<float> u(std::size_t(volume.dims.x));
    for (std::int64_t r = first_row; r < last_row; ++r) {
      normalised_row<T>(volume, range, clip_planes, r, u);
      float* dst = out + r * std::int64_t(taps.n_out) * moments;
      for (int j = 0; j < taps.n_out; ++j) {
        float acc[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        const int count = taps.count(j);
        for (int t = 0; t < count; ++t) {
          const float w = taps.weights[std::size_t(taps.begin[std::size_t(j)] + t)];
          const float value = u[std::size_t(taps.first[std::size_t(j)] + t)];
          float power = value;
          for (int m = 0; m < moments; ++m) {
            acc[m] += w * power;
            power *= value;
          }
        }
        for (int m = 0; m < moments; ++m) dst[j * moments + m] = acc[m];
      }
    }
  }, 16);
}

// The window of output node j along an axis of n_in input nodes: the inputs
// within `radius` input nodes of it.
void maximum_window(int n_in, int n_out, int j, double radius, int& lo, int& hi) {
  const double centre = n_out > 1 ? double(j) * double(n_in - 1) / double(n_out - 1) : 0.0;
  lo = std::max(0, int(std::floor(centre - radius)));
  hi = std::min(n_in - 1, int(std::ceil(centre + radius)));
}

// Sliding maximum along one axis: out node j (at input coordinate
// j (n_in - 1) / (n_out - 1)) takes the largest input within `radius` input
// nodes of it. Grids as in resample_axis.
void maximum_axis(const float* in, float* out, std::int64_t outer, std::int64_t inner, int n_in, int n_out,
                  double radius) {
  parallel_for(0, outer * n_out, [&](std::int64_t first_item, std::int64_t last_item) {
    for (std::int64_t item = first_item; item < last_item; ++item) {
      const std::int64_t o = item / n_out, j = item % n_out;
      int lo, hi;
      maximum_window(n_in, n_out, int(j), radius, lo, hi);
      float* dst = out + (o * n_out + j) * inner;
      std::fill(dst, dst + inner, 0.0f);
      for (int t = lo; t <= hi; ++t) {
        const float* src = in + (o * n_in + t) * inner;
        for (std::int64_t i = 0; i < inner; ++i) dst[i] = std::max(dst[i], src[i]);
      }
    }
  }, std::max<std::int64_t>(1, 65536 / std::max<std::int64_t>(inner, 1)));
}

// The first pass of level 0's maxima: voxels -> the largest u in each output
// node's window along x (radius in voxels).
template <class T>
void maxima_along_x(const VolumeView& volume, vec2 range, const std::vector<vec4>& clip_planes, int n_out,
                    double radius, float* out) {
  const std::int64_t rows = std::int64_t(volume.dims.y) * volume.dims.z;
  parallel_for(0, rows, [&](std::int64_t first_row, std::int64_t last_row) {
    std::vector<float> u(std::size_t(volume.dims.x));
    for (std::int64_t r = first_row; r < last_row; ++r) {
      normalised_row<T>(volume, range, clip_planes, r, u);
      for (int j = 0; j < n_out; ++j) {
        int lo, hi;
        maximum_window(volume.dims.x, n_out, j, radius, lo, hi);
        out[r * n_out + j] = *std::max_element(u.begin() + lo, u.begin() + hi + 1);
      }
    }
  }, 16);
}

std::vector<float> allocate(ivec3 dims, int channels, const char* what) {
  const std::uint64_t count = checked_product({std::uint64_t(dims.x), std::uint64_t(dims.y), std::uint64_t(dims.z),
                                               std::uint64_t(channels)});
  check_memory_budget(what, checked_product({count, sizeof(float)}));
  return std::vector<float>(std::size_t(count));
}

}  // namespace

void MomentPyramidSettings::validate() const {
  if (moments != 2 && moments != 4) {
    throw InvalidArgument("moments", fmt::format("must be 2 (Chebyshev) or 4 (Hamburger), got {}", moments));
  }
  if (!(resolution > 0.0f && resolution <= 1.0f)) {
    throw InvalidArgument("resolution", fmt::format("must be in (0, 1], got {}", resolution));
  }
  if (kernel_size < 3 || kernel_size % 2 == 0) {
    throw InvalidArgument("kernel_size", fmt::format("must be odd and at least 3, got {}", kernel_size));
  }
}

MomentPyramid::MomentPyramid(const VolumeView& volume, vec2 value_range, const MomentPyramidSettings& settings,
                             std::vector<vec4> clip_planes)
    : settings_(settings), data_dims_(volume.dims), spacing_(volume.spacing), origin_(volume.origin),
      value_range_(value_range), clip_planes_(std::move(clip_planes)) {
  settings.validate();
  if (volume.data == nullptr || glm::any(glm::lessThan(volume.dims, ivec3(1)))) {
    throw InvalidArgument("volume", "the occlusion map needs a non-empty volume");
  }
  const int channels = settings.moments;
  const float unit = volume.min_spacing();

  // Level geometry: dims and, per axis, the node spacing in world units.
  ivec3 dims;
  for (int a = 0; a < 3; ++a) {
    dims[a] = volume.dims[a] == 1 ? 1 : std::max(2, int(std::lround(double(volume.dims[a]) * settings.resolution)));
  }
  for (int k = 0; k < kMaxMomentLevels; ++k) {
    level_dims_.push_back(dims);
    if (k >= 3 && dims.x <= 2 && dims.y <= 2 && dims.z <= 2) break;
    for (int a = 0; a < 3; ++a) dims[a] = dims[a] <= 2 ? dims[a] : (dims[a] + 1) / 2;
  }
  auto node_spacing = [&](ivec3 d, int a) {  // world units between nodes of a grid with d nodes
    return d[a] > 1 ? double(volume.dims[a] - 1) * double(spacing_[a]) / double(d[a] - 1) : double(spacing_[a]);
  };
  const double sigma0 = double(settings.kernel_size - 1) / 4.0 * double(unit) / double(settings.resolution);

  // Level 0 from the voxels: x, then y, then z.
  {
    const ivec3 d0 = level_dims_[0];
    std::array<ResamplingTaps, 3> taps;
    for (int a = 0; a < 3; ++a) {
      taps[std::size_t(a)] = gaussian_resampling_taps(volume.dims[a], d0[a], sigma0 / double(spacing_[a]));
    }
    std::vector<float> along_x = allocate(ivec3(d0.x, volume.dims.y, volume.dims.z), channels, "occlusion map");
    visit_voxel_type(volume.type, [&](auto tag) {
      using T = decltype(tag);
      moments_along_x<T>(volume, value_range, clip_planes_, channels, taps[0], along_x.data());
    });
    std::vector<float> along_y = allocate(ivec3(d0.x, d0.y, volume.dims.z), channels, "occlusion map");
    resample_axis(along_x.data(), along_y.data(), volume.dims.z, std::int64_t(d0.x) * channels, taps[1]);
    along_x = {};
    std::vector<float> level0 = allocate(d0, channels, "occlusion map");
    resample_axis(along_y.data(), level0.data(), 1, std::int64_t(d0.x) * d0.y * channels, taps[2]);
    levels_.push_back(std::move(level0));
    taps_.push_back(std::move(taps));
  }
  // Level k from level k - 1: sigma_k^2 = sigma_(k-1)^2 + sigma_inc^2 with sigma_k = 2 sigma_(k-1).
  for (std::size_t k = 1; k < level_dims_.size(); ++k) {
    const ivec3 src = level_dims_[k - 1], dst = level_dims_[k];
    const double increment = sigma0 * std::sqrt(3.0) * std::exp2(double(k) - 1.0);
    std::array<ResamplingTaps, 3> taps;
    for (int a = 0; a < 3; ++a) {
      taps[std::size_t(a)] = gaussian_resampling_taps(src[a], dst[a], increment / node_spacing(src, a));
    }
    std::vector<float> along_x = allocate(ivec3(dst.x, src.y, src.z), channels, "occlusion map");
    resample_axis(levels_.back().data(), along_x.data(), std::int64_t(src.y) * src.z, channels, taps[0]);
    std::vector<float> along_y = allocate(ivec3(dst.x, dst.y, src.z), channels, "occlusion map");
    resample_axis(along_x.data(), along_y.data(), src.z, std::int64_t(dst.x) * channels, taps[1]);
    along_x = {};
    std::vector<float> level = allocate(dst, channels, "occlusion map");
    resample_axis(along_y.data(), level.data(), 1, std::int64_t(dst.x) * dst.y * channels, taps[2]);
    levels_.push_back(std::move(level));
    taps_.push_back(std::move(taps));
  }
  build_maxima(volume);
}

void MomentPyramid::build_maxima(const VolumeView& volume) {
  // Level k's maximum node covers a box of half-width kMaximumRadiusSigmas
  // sigma_k plus one node spacing h_k around itself: any point within half a
  // node spacing of it (what the view's nearest-node read returns) then has
  // its whole region's box inside. Level 0 comes from the voxels (x first,
  // straight from them), level k from level k - 1, whose nodes cover
  // R_(k-1) each: taking those within R_k - R_(k-1) + h_(k-1) covers R_k.
  auto spacing_of = [&](ivec3 d, int a) {  // world units between nodes of a grid with d nodes
    return d[a] > 1 ? double(volume.dims[a] - 1) * double(spacing_[a]) / double(d[a] - 1) : double(spacing_[a]);
  };
  vec3 previous_radius(0.0f);
  ivec3 in = volume.dims;
  std::vector<float> previous;  // level k - 1's maxima, unrounded
  for (std::size_t k = 0; k < level_dims_.size(); ++k) {
    const ivec3 out = level_dims_[k];
    std::vector<float> grid;
    ivec3 dims = in;
    for (int a = 0; a < 3; ++a) {
      const double radius = kMaximumRadiusSigmas * double(sigma_world(int(k))) + spacing_of(out, a);
      const double reach = k == 0 ? radius : radius - double(previous_radius[a]) + spacing_of(in, a);
      previous_radius[a] = float(radius);
      ivec3 next = dims;
      next[a] = out[a];
      std::vector<float> reduced = allocate(next, 1, "occlusion map maxima");
      if (k == 0 && a == 0) {
        visit_voxel_type(volume.type, [&](auto tag) {
          using T = decltype(tag);
          maxima_along_x<T>(volume, value_range_, clip_planes_, out.x, reach / spacing_of(in, 0), reduced.data());
        });
      } else {
        std::int64_t outer = 1, inner = 1;
        for (int b = a + 1; b < 3; ++b) outer *= dims[b];
        for (int b = 0; b < a; ++b) inner *= dims[b];
        const float* source = a == 0 ? previous.data() : grid.data();
        maximum_axis(source, reduced.data(), outer, inner, dims[a], out[a], reach / spacing_of(in, a));
      }
      grid = std::move(reduced);
      dims = next;
    }
    std::vector<std::uint8_t> stored(grid.size());
    for (std::size_t i = 0; i < grid.size(); ++i) {
      stored[i] = std::uint8_t(std::min(kMaximumSteps, int(std::ceil(double(grid[i]) * kMaximumSteps))));
    }
    maxima_.push_back(std::move(stored));
    previous = std::move(grid);
    in = out;
  }
}

float MomentPyramid::sigma_world(int level) const {
  const double unit = double(std::min(spacing_.x, std::min(spacing_.y, spacing_.z)));
  return float(double(settings_.kernel_size - 1) / 4.0 * unit / double(settings_.resolution) * std::exp2(level));
}

float MomentPyramid::normalise(float value) const {
  const float width = value_range_.y - value_range_.x;
  return width > 0.0f ? (value - value_range_.x) / width : value - value_range_.x;
}

std::uint64_t MomentPyramid::bytes() const {
  std::uint64_t total = 0;
  for (const auto& l : levels_) total += l.size() * sizeof(float);
  for (const auto& l : maxima_) total += l.size();
  return total;
}

std::vector<double> MomentPyramid::effective_weights(int level, int axis) const {
  std::vector<double> w = dense_weights(taps_[0][std::size_t(axis)]);
  int rows = taps_[0][std::size_t(axis)].n_out;
  for (int k = 1; k <= level; ++k) {
    const ResamplingTaps& t = taps_[std::size_t(k)][std::size_t(axis)];
    w = compose_weights(dense_weights(t), t.n_out, w, rows, data_dims_[axis]);
    rows = t.n_out;
  }
  return w;
}

}  // namespace penumbra

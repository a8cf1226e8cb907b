#pragma once
// The occlusion map (Penner & Mitchell 2008, sections 3.4, 4.1, 4.2): a
// pyramid of Gaussian-filtered moment volumes of the data. Level 0 holds, at
// `resolution` times the data grid, the Gaussian-weighted means of u^1..u^K
// (u: the data value normalised to the volume's value range, so the map
// depends on the data only, never on the TF or the iso-value); its Gaussian
// has (kernel_size - 1) / 4 level-0 voxels of standard deviation, i.e. the
// paper's 5x5x5 kernel at half resolution by default. Each further level
// halves the grid and doubles the Gaussian: it resamples the level above with
// the incremental sigma sqrt(4^k - 4^(k-1)) sigma0, so that level k's region
// is (up to the kernels' truncation at 2 sigma) a Gaussian of sigma0 2^k.
// Sigmas are isotropic in world units (per axis in index units), so
// anisotropic spacing gets a round region (section 4.2). Beyond the paper,
// each level also holds per node the largest u in a box around it (issue 17:
// a region with nothing above a query occludes nothing, which the moments
// alone cannot tell; see MomentPyramidView::maximum).
#include "penumbra/techniques/occlusion_map/gaussian_resampling.h"
#include "penumbra/techniques/occlusion_map/moment_pyramid_view.h"
#include "penumbra/volume/volume_view.h"

#include <array>
#include <cstdint>
#include <vector>

namespace penumbra {

struct MomentPyramidSettings {
  int moments = 2;          // 2 (the paper) or 4
  float resolution = 0.5f;  // level 0 grid as a fraction of the data grid, in (0, 1]
  int kernel_size = 5;      // taps of level 0's Gaussian at level-0 resolution (odd, >= 3)

  // Throws InvalidArgument naming "moments", "resolution" or "kernel_size".
  void validate() const;
  bool operator==(const MomentPyramidSettings&) const = default;
};

class MomentPyramid {
 public:
  MomentPyramid() = default;
  // value_range: the data values mapped to u = 0 and u = 1 (the volume's
  // range). Non-finite voxels, and voxels outside a clip plane (a vec4 n, d:
  // kept where dot(n, p) + d >= 0), count as u = 0. Checks the memory budget
  // first.
  MomentPyramid(const VolumeView& volume, vec2 value_range, const MomentPyramidSettings& settings,
                std::vector<vec4> clip_planes = {});

  bool empty() const { return levels_.empty(); }
  const MomentPyramidSettings& settings() const { return settings_; }
  int moments() const { return settings_.moments; }
  int level_count() const { return int(levels_.size()); }
  ivec3 level_dims(int level) const { return level_dims_[std::size_t(level)]; }
  const std::vector<float>& level(int level) const { return levels_[std::size_t(level)]; }
  vec2 value_range() const { return value_range_; }
  const std::vector<vec4>& clip_planes() const { return clip_planes_; }
  // Standard deviation of level k's Gaussian region in world units.
  float sigma_world(int level) const;
  std::uint64_t bytes() const;

  // u for a data value (the normalisation the map was built with).
  float normalise(float value) const;

  // The weight of every data node along `axis` in every node of `level`
  // (dense, level_dims(level)[axis] x data dims[axis], rows summing to 1):
  // the separable region each level node averages, for brute-force checks.
  std::vector<double> effective_weights(int level, int axis) const;

  template <int K> MomentPyramidView<K> view() const {
    MomentPyramidView<K> v;
    v.level_count = level_count();
    v.origin = origin_;
    v.sigma0 = sigma_world(0);
    for (int k = 0; k < v.level_count; ++k) {
      const ivec3 d = level_dims_[std::size_t(k)];
      v.levels[k].texels = levels_[std::size_t(k)].data();
      v.levels[k].maxima = maxima_[std::size_t(k)].data();
      v.levels[k].dims = d;
      for (int a = 0; a < 3; ++a) {
        v.levels[k].scale[a] = data_dims_[a] > 1 ? float(d[a] - 1) / (float(data_dims_[a] - 1) * spacing_[a]) : 0.0f;
      }
    }
    return v;
  }

 private:
  void build_maxima(const VolumeView& volume);

  MomentPyramidSettings settings_;
  ivec3 data_dims_{0};
  vec3 spacing_{1.0f};
  vec3 origin_{0.0f};
  vec2 value_range_{0.0f, 1.0f};
  std::vector<vec4> clip_planes_;
  std::vector<ivec3> level_dims_;
  std::vector<std::vector<float>> levels_;
  // Per node of each level: the largest u within a box around it that holds
  // the region of every point the view's maximum() reads from that node, in
  // 255ths rounded up (kMaximumSteps).
  std::vector<std::vector<std::uint8_t>> maxima_;
  std::vector<std::array<ResamplingTaps, 3>> taps_;  // per level, per axis: from the level above (or the data)
};

}  // namespace penumbra

#pragma once
// One axis of the occlusion map's separable filter: Gaussian-weighted
// resampling of a line of n_in nodes onto n_out nodes spanning the same world
// extent (node-centred, like every penumbra grid: output node j sits at input
// coordinate j (n_in - 1) / (n_out - 1)). Output j is the normalised
// Gaussian-weighted mean of the inputs within 2 sigma of it; near the ends
// the weights are renormalised, so the region counts only voxels that exist.
// Blurring and down-sampling are one operation, and level k of the pyramid is
// level k - 1 resampled with an incremental sigma (see moment_pyramid.h).
#include <vector>

namespace penumbra {

// Kernel radius in sigmas: 2 gives the paper's 5 taps at sigma = 1 (Penner &
// Mitchell 2008, section 5.1, "5x5x5 separable gaussian blur").
inline constexpr double kKernelRadiusSigmas = 2.0;

struct ResamplingTaps {
  int n_in = 0;
  int n_out = 0;
  std::vector<int> first;       // per output node: its first input node
  std::vector<int> begin;       // per output node: its first weight; begin[n_out] = weights.size()
  std::vector<float> weights;   // normalised, summing to 1 per output node

  int count(int j) const { return begin[j + 1] - begin[j]; }
  // Input coordinate of output node j.
  double position(int j) const;
};

// sigma_in: the Gaussian's standard deviation in input nodes (> 0). Throws
// InvalidArgument for sizes below 1 or a non-positive sigma.
ResamplingTaps gaussian_resampling_taps(int n_in, int n_out, double sigma_in);

// The dense n_out x n_in matrix of the taps (row j: the weight of every input
// node in output j), and the product of such matrices: the effective weights
// of a chain of resamplings, for tests and the accuracy measurement.
std::vector<double> dense_weights(const ResamplingTaps& taps);
std::vector<double> compose_weights(const std::vector<double>& outer, int outer_rows, const std::vector<double>& inner,
                                    int inner_rows, int inner_cols);

}  // namespace penumbra

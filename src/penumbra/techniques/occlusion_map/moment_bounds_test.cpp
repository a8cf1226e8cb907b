// The occluded-fraction bounds (moment_bounds.h) against exact fractions of
// discrete distributions, and the moment pyramid against brute force over the
// same Gaussian-weighted voxels.
#include "penumbra/base/error.h"
#include "penumbra/base/rng.h"
#include "penumbra/techniques/occlusion_map/moment_bounds.h"
#include "penumbra/techniques/occlusion_map/moment_pyramid.h"
#include "penumbra/volume/volume.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace penumbra {
namespace {

struct Atom {
  double value;
  double weight;
};

vec4 moments_of(const std::vector<Atom>& atoms) {
  glm::dvec4 m(0.0);
  for (const Atom& a : atoms) {
    const double v = a.value;
    m += a.weight * glm::dvec4(v, v * v, v * v * v, v * v * v * v);
  }
  return vec4(m);
}

double exact_fraction(const std::vector<Atom>& atoms, double t) {
  double f = 0.0;
  for (const Atom& a : atoms) f += a.value >= t ? a.weight : 0.0;
  return f;
}

// The paper's bimodal argument (section 3.4): two values d1 < d2 with share p
// of d2, queried at d2, give exactly p. Float rounding of the moments is the
// only error (the variance p (1 - p) (d2 - d1)^2 is at least ~1e-3 here).
TEST(MomentBounds, ChebyshevIsExactForTwoValuesQueriedAtTheUpperOne) {
  for (const double d1 : {0.0, 0.1, 0.35}) {
    for (const double d2 : {0.5, 0.8, 1.0}) {
      for (const double p : {0.05, 0.3, 0.5, 0.9}) {
        const vec4 m = moments_of({{d1, 1.0 - p}, {d2, p}});
        EXPECT_NEAR(chebyshev_occlusion(m.x, m.y, float(d2)), p, 2e-5) << d1 << " " << d2 << " " << p;
        // Four moments: exact too (at most three support points).
        EXPECT_NEAR(hamburger_occlusion(m, float(d2)), p, 2e-3) << d1 << " " << d2 << " " << p;
      }
    }
  }
}

// The four-moment bound is exact at every support point of a three-valued
// distribution, where Chebyshev is not.
TEST(MomentBounds, FourMomentsAreExactForThreeValues) {
  const std::vector<Atom> atoms = {{0.1, 0.5}, {0.45, 0.3}, {0.9, 0.2}};
  const vec4 m = moments_of(atoms);
  for (const double t : {0.45, 0.9}) {
    EXPECT_NEAR(hamburger_occlusion(m, float(t)), exact_fraction(atoms, t), 3e-3) << t;
  }
  EXPECT_GT(chebyshev_occlusion(m.x, m.y, 0.45f) - exact_fraction(atoms, 0.45), 0.1);
}

// Both are upper bounds on the occluded fraction, and four moments never give
// a looser one than two: random discrete distributions on [0, 1], every query.
// Tolerance 2e-3 below the exact fraction: float moments.
TEST(MomentBounds, BoundsHoldAndFourMomentsAreTighter) {
  Pcg32 rng(7);
  double gain = 0.0;
  int queries = 0;
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<Atom> atoms(std::size_t(2 + trial % 6));
    double total = 0.0;
    for (Atom& a : atoms) {
      a = {double(rng.next_float()), 0.05 + double(rng.next_float())};
      total += a.weight;
    }
    for (Atom& a : atoms) a.weight /= total;
    const vec4 m = moments_of(atoms);
    for (int q = 0; q <= 20; ++q) {
      const float t = float(q) / 20.0f;
      const double exact = exact_fraction(atoms, t);
      const float two = chebyshev_occlusion(m.x, m.y, t);
      const float four = hamburger_occlusion(m, t);
      ASSERT_GE(two, 0.0f);
      ASSERT_LE(two, 1.0f);
      ASSERT_GE(four, 0.0f);
      ASSERT_LE(four, 1.0f);
      EXPECT_GE(two, exact - 1e-4) << trial << " t=" << t;
      EXPECT_GE(four, exact - 2e-3) << trial << " t=" << t;
      // The bias (kMomentBias) widens nearly single-valued distributions a
      // little, which can lift the four-moment bound by a few 1e-3 there.
      EXPECT_LE(four, two + 1e-2) << trial << " t=" << t;
      gain += double(two - four);
      ++queries;
    }
  }
  EXPECT_GT(gain / queries, 0.02);  // four moments are measurably tighter on average
}

// A volume of two values: every pyramid node of every level holds the moments
// of a two-valued region, so Chebyshev at the upper value equals the exact
// Gaussian-weighted share of it, counted here voxel by voxel with the
// pyramid's own effective weights.
TEST(MomentPyramid, TwoValuedVolumeGivesTheExactFractionAtEveryLevel) {
  const ivec3 dims(24, 20, 16);
  Volume volume(dims, VoxelType::Float32);
  float* voxels = volume.frame_as<float>(0);
  Pcg32 rng(3);
  for (std::int64_t i = 0; i < std::int64_t(dims.x) * dims.y * dims.z; ++i) {
    voxels[i] = rng.next_float() < 0.3f ? 0.8f : 0.2f;
  }
  const MomentPyramid pyramid(volume.view(), vec2(0.0f, 1.0f), MomentPyramidSettings{});
  ASSERT_GE(pyramid.level_count(), 4);
  for (int level = 0; level < 4; ++level) {
    const ivec3 d = pyramid.level_dims(level);
    const std::vector<double> wx = pyramid.effective_weights(level, 0);
    const std::vector<double> wy = pyramid.effective_weights(level, 1);
    const std::vector<double> wz = pyramid.effective_weights(level, 2);
    double worst = 0.0;
    for (int k = 0; k < d.z; ++k) {
      for (int j = 0; j < d.y; ++j) {
        for (int i = 0; i < d.x; ++i) {
          double exact = 0.0;
          for (int z = 0; z < dims.z; ++z) {
            for (int y = 0; y < dims.y; ++y) {
              const double wyz = wz[std::size_t(k * dims.z + z)] * wy[std::size_t(j * dims.y + y)];
              if (wyz == 0.0) continue;
              for (int x = 0; x < dims.x; ++x) {
                if (voxels[(z * dims.y + y) * dims.x + x] > 0.5f) exact += wyz * wx[std::size_t(i * dims.x + x)];
              }
            }
          }
          const float* m = pyramid.level(level).data() + 2 * ((std::int64_t(k) * d.y + j) * d.x + i);
          worst = std::max(worst, std::abs(double(chebyshev_occlusion(m[0], m[1], 0.8f)) - exact));
        }
      }
    }
    // Float moments over many voxels: rounding of ~1e-6 relative, amplified
    // by 1 / variance (variance >= ~0.05 here).
    EXPECT_LT(worst, 1e-4) << "level " << level;
  }
}

// The paper's 5x5x5 kernel: at sigma 1 node, a same-size resampling has 5
// symmetric taps (2 sigma each side) summing to 1, renormalised at the ends;
// halving the grid centres output j on input 2j.
TEST(GaussianResampling, FiveTapKernelAndDownsampling) {
  const ResamplingTaps same = gaussian_resampling_taps(16, 16, 1.0);
  ASSERT_EQ(same.count(8), 5);
  EXPECT_EQ(same.first[8], 6);
  const float* w = same.weights.data() + same.begin[8];
  EXPECT_FLOAT_EQ(w[0], w[4]);
  EXPECT_FLOAT_EQ(w[1], w[3]);
  EXPECT_NEAR(w[2] / w[1], std::exp(0.5), 1e-5);
  EXPECT_NEAR(w[0] + w[1] + w[2] + w[3] + w[4], 1.0, 1e-6);
  EXPECT_EQ(same.count(0), 3);  // the region counts only nodes that exist
  const ResamplingTaps half = gaussian_resampling_taps(17, 9, 2.0);
  EXPECT_DOUBLE_EQ(half.position(4), 8.0);
  EXPECT_EQ(half.count(4), 9);
  EXPECT_THROW(gaussian_resampling_taps(16, 16, 0.0), InvalidArgument);
  EXPECT_THROW(gaussian_resampling_taps(0, 16, 1.0), InvalidArgument);
}

// Level k's effective region is close to a Gaussian of sigma0 2^k: its
// variance along an axis, in world units, at an interior node.
TEST(MomentPyramid, LevelRegionsDoubleTheirWidth) {
  const ivec3 dims(96, 8, 8);
  Volume volume(dims, VoxelType::UInt8);
  std::fill_n(volume.frame_as<std::uint8_t>(0), volume.voxel_count(), std::uint8_t(1));
  const MomentPyramid pyramid(volume.view(), vec2(0.0f, 255.0f), MomentPyramidSettings{});
  for (int level = 0; level < 4; ++level) {
    const std::vector<double> w = pyramid.effective_weights(level, 0);
    const int n_out = pyramid.level_dims(level).x;
    const int node = n_out / 2;
    double sum = 0.0, mean = 0.0, second = 0.0;
    for (int x = 0; x < dims.x; ++x) {
      const double wx = w[std::size_t(node * dims.x + x)];
      sum += wx;
      mean += wx * x;
      second += wx * x * x;
    }
    const double sigma = std::sqrt(second / sum - (mean / sum) * (mean / sum));
    // Float weights; the centre drifts by a small part of sigma because the
    // coarser levels' nodes are not symmetric about it.
    EXPECT_NEAR(sum, 1.0, 1e-6);
    EXPECT_NEAR(mean / sum, double(node) * (dims.x - 1) / double(n_out - 1), 0.02 * pyramid.sigma_world(level));
    // Truncating each kernel at 2 sigma narrows it (a truncated Gaussian's
    // sigma is 0.88 of the full one); the composition recovers part of that.
    EXPECT_GT(sigma, 0.8 * pyramid.sigma_world(level)) << level;
    EXPECT_LT(sigma, 1.02 * pyramid.sigma_world(level)) << level;
  }
}

// The maximum a view reads for a point is at least the largest u in the box
// of half-width kMaximumRadiusSigmas sigma around it (brute force over the
// voxels), at every level and at fractional ones, on a sparse random volume
// with anisotropic spacing; and not the largest of a much bigger box (it
// stays local: zero where nothing lies within 3 sigma + 2 node spacings).
TEST(MomentPyramid, MaximaCoverEveryRegionAndStayLocal) {
  const ivec3 dims(41, 23, 17);
  Volume volume(dims, VoxelType::Float32);
  volume.set_spacing(vec3(1.0f, 0.7f, 1.3f));
  float* voxels = volume.frame_as<float>(0);
  Pcg32 rng(11);
  for (std::int64_t i = 0; i < std::int64_t(volume.voxel_count()); ++i) {  // isolated voxels in the first 8 x slices
    voxels[i] = rng.next_float() < (i % dims.x < 8 ? 0.01f : 0.0f) ? 0.1f + 0.9f * rng.next_float() : 0.0f;
  }
  const MomentPyramid pyramid(volume.view(), vec2(0.0f, 1.0f), MomentPyramidSettings{});
  const MomentPyramidView<2> view = pyramid.view<2>();
  const VolumeView v = volume.view();
  auto largest_within = [&](vec3 c, vec3 half) {
    float best = 0.0f;
    for (int z = 0; z < dims.z; ++z) {
      for (int y = 0; y < dims.y; ++y) {
        for (int x = 0; x < dims.x; ++x) {
          const vec3 d = glm::abs(v.world_from_index(vec3(float(x), float(y), float(z))) - c);
          if (d.x <= half.x && d.y <= half.y && d.z <= half.z) {
            best = std::max(best, voxels[(std::int64_t(z) * dims.y + y) * dims.x + x]);
          }
        }
      }
    }
    return best;
  };
  const Box3 box = volume.world_box();
  int local = 0, checked = 0;
  for (int n = 0; n < 2000; ++n) {
    // Every other point near the voxels, where a box too small would miss them.
    const float x = n % 2 == 0 ? 0.3f * rng.next_float() : rng.next_float();
    const vec3 c = box.lower + vec3(x, rng.next_float(), rng.next_float()) * (box.upper - box.lower);
    const float level = float(n % 4) + (n % 3 == 0 ? 0.5f : 0.0f);
    const float sigma = view.sigma(glm::ceil(level));
    const float read = view.maximum(level, c);
    ASSERT_GE(read, largest_within(c, vec3(kMaximumRadiusSigmas * view.sigma(level)))) << n;
    const int k = int(glm::ceil(level));
    vec3 spacing;
    for (int a = 0; a < 3; ++a) spacing[a] = 1.0f / view.levels[k].scale[a];
    // The node read is the nearest one (roundf of the clamped node coordinates).
    const MomentLevelView& l = view.levels[k];
    const ivec3 node = glm::clamp(ivec3(glm::round((c - view.origin) * l.scale)), ivec3(0), l.dims - 1);
    const std::uint8_t stored = l.maxima[node.x + l.dims.x * (node.y + l.dims.y * node.z)];
    EXPECT_EQ(read, float(stored) * (1.0f / float(kMaximumSteps))) << n;
    if (largest_within(c, vec3(3.0f * sigma) + 2.0f * spacing) == 0.0f) {
      ++local;
      EXPECT_EQ(read, 0.0f) << n;
    }
    ++checked;
  }
  EXPECT_GT(local, 20);  // the second check ran
  EXPECT_EQ(checked, 2000);
}

TEST(MomentPyramid, BadSettingsNameTheParameter) {
  Volume volume(ivec3(8), VoxelType::UInt8);
  std::fill_n(volume.frame_as<std::uint8_t>(0), volume.voxel_count(), std::uint8_t(0));
  auto expect_named = [&](MomentPyramidSettings s, const char* name) {
    try {
      MomentPyramid(volume.view(), vec2(0.0f, 1.0f), s);
      ADD_FAILURE() << "no error for " << name;
    } catch (const InvalidArgument& e) {
      EXPECT_EQ(e.name(), name) << e.what();
    }
  };
  expect_named({3, 0.5f, 5}, "moments");
  expect_named({2, 0.0f, 5}, "resolution");
  expect_named({2, 1.5f, 5}, "resolution");
  expect_named({2, 0.5f, 4}, "kernel_size");
  expect_named({2, 0.5f, 1}, "kernel_size");
}

}  // namespace
}  // namespace penumbra

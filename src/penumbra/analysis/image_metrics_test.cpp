#include "penumbra/analysis/image_metrics.h"

#include "penumbra/base/error.h"
#include "penumbra/base/rng.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace penumbra {
namespace {

// Smooth structure plus a sharp edge, in [0.05, 0.85] so offsets stay in range.
Image test_pattern(int width, int height) {
  Image image(width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const float u = float(x) / float(width);
      const float v = float(y) / float(height);
      const float edge = x < width / 2 ? 0.0f : 0.3f;
      image.at(x, y) = vec4(0.05f + 0.5f * u + edge, 0.05f + 0.4f * v + edge, 0.05f + 0.25f * (u + v), 1.0f);
    }
  }
  return image;
}

Image add_noise(const Image& image, float amplitude, std::uint64_t seed) {
  Pcg32 rng(seed);
  Image noisy = image;
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      for (int c = 0; c < 3; ++c) noisy.at(x, y)[c] += amplitude * (2.0f * rng.next_float() - 1.0f);
    }
  }
  return noisy;
}

TEST(ImageMetrics, ConstantOffsetGivesTheOffset) {
  const Image reference = test_pattern(40, 30);
  Image test = reference;
  for (int y = 0; y < test.height(); ++y) {
    for (int x = 0; x < test.width(); ++x) {
      test.at(x, y) += vec4(0.05f, 0.05f, 0.05f, 0.7f);  // alpha is ignored
    }
  }
  EXPECT_NEAR(rmse(test, reference), 0.05, 1e-6);
  EXPECT_NEAR(mean_absolute_error(test, reference), 0.05, 1e-6);
  EXPECT_NEAR(max_abs_error(test, reference), 0.05, 1e-6);
}

TEST(ImageMetrics, ErrorsCountChannelsSeparately) {
  Image reference(2, 1, vec4(0.0f, 0.0f, 0.0f, 1.0f));
  Image test = reference;
  test.at(0, 0).g = 0.6f;  // one sample of six
  EXPECT_NEAR(rmse(test, reference), std::sqrt(0.36 / 6.0), 1e-7);
  EXPECT_NEAR(mean_absolute_error(test, reference), 0.1, 1e-7);
  EXPECT_NEAR(max_abs_error(test, reference), 0.6, 1e-7);
}

TEST(ImageMetrics, PsnrIsInfiniteForIdenticalImagesAndFollowsRmse) {
  const Image reference = test_pattern(32, 24);
  EXPECT_EQ(psnr(reference, reference), std::numeric_limits<double>::infinity());
  EXPECT_EQ(rmse(reference, reference), 0.0);
  const Image test = add_noise(reference, 0.1f, 7);
  const double error = rmse(test, reference);
  ASSERT_GT(error, 0.0);
  EXPECT_NEAR(psnr(test, reference), 20.0 * std::log10(1.0 / error), 1e-9);
}

TEST(ImageMetrics, RejectsMismatchedAndEmptyImages) {
  const Image a(3, 2);
  const Image b(2, 3);
  try {
    rmse(a, b);
    FAIL() << "expected InvalidArgument";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("3x2"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("2x3"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ssim(a, b), InvalidArgument);
  EXPECT_THROW(delta_e_stats(a, b), InvalidArgument);
  EXPECT_THROW(compare_images(a, b), InvalidArgument);
  EXPECT_THROW(psnr(Image(), Image()), InvalidArgument);
}

TEST(ImageMetrics, DeltaEStatsOfARampArePercentiles) {
  std::vector<float> values;
  for (int i = 100; i >= 0; --i) values.push_back(float(i));  // order must not matter
  const DeltaEStats stats = delta_e_stats(values);
  EXPECT_DOUBLE_EQ(stats.mean, 50.0);
  EXPECT_DOUBLE_EQ(stats.median, 50.0);
  EXPECT_DOUBLE_EQ(stats.p99, 99.0);
  EXPECT_DOUBLE_EQ(stats.max, 100.0);
}

TEST(ImageMetrics, DeltaEStatsOfOneDifferentPixel) {
  // 99 equal pixels and one red-for-grey pixel: the 99th percentile sits at
  // position 0.99 x 99 = 98.01, a hundredth of the way to the outlier.
  const vec3 grey(0.2f);
  const vec3 red(0.8f, 0.1f, 0.1f);
  const Image reference(10, 10, vec4(grey, 1.0f));
  Image test = reference;
  test.at(3, 7) = vec4(red, 1.0f);
  const double outlier = delta_e_2000(srgb_linear_to_lab(red), srgb_linear_to_lab(grey));
  ASSERT_GT(outlier, 10.0);
  const DeltaEStats stats = delta_e_stats(test, reference);
  EXPECT_NEAR(stats.mean, outlier / 100.0, 1e-5);
  EXPECT_EQ(stats.median, 0.0);
  EXPECT_NEAR(stats.p99, 0.01 * outlier, 1e-5);
  EXPECT_NEAR(stats.max, outlier, 1e-5);
}

TEST(ImageMetrics, DeltaEClampsToTheDisplayRangeAndKeepsNaN) {
  const Image reference(2, 1, vec4(1.0f, 1.0f, 1.0f, 1.0f));
  Image test(2, 1, vec4(3.0f, 1.5f, 1.0f, 1.0f));  // HDR white reads as white
  EXPECT_EQ(delta_e_stats(test, reference).max, 0.0);
  test.at(1, 0).g = std::numeric_limits<float>::quiet_NaN();
  EXPECT_TRUE(std::isnan(delta_e_stats(test, reference).mean));
  EXPECT_TRUE(std::isnan(delta_e_stats(test, reference).max));
}

// Direct SSIM: one weighted window per output pixel, no separable filtering,
// to check the production code's ring buffer and truncated windows.
double brute_force_ssim(const Image& a, const Image& b) {
  auto luma = [](const Image& image, int x, int y) { return double(luminance(srgb_encode(vec3(image.at(x, y))))); };
  auto taps = [](int size) {
    std::vector<double> t(static_cast<std::size_t>(size));
    double sum = 0.0;
    for (int i = 0; i < size; ++i) {
      const double d = i - 0.5 * (size - 1);
      sum += t[std::size_t(i)] = std::exp(-d * d / 4.5);
    }
    for (double& v : t) v /= sum;
    return t;
  };
  const std::vector<double> tx = taps(std::min(11, a.width()));
  const std::vector<double> ty = taps(std::min(11, a.height()));
  double total = 0.0;
  int count = 0;
  for (int y0 = 0; y0 + int(ty.size()) <= a.height(); ++y0) {
    for (int x0 = 0; x0 + int(tx.size()) <= a.width(); ++x0) {
      double mx = 0, my = 0, mxx = 0, myy = 0, mxy = 0;
      for (std::size_t j = 0; j < ty.size(); ++j) {
        for (std::size_t i = 0; i < tx.size(); ++i) {
          const double w = tx[i] * ty[j];
          const double p = luma(a, x0 + int(i), y0 + int(j));
          const double q = luma(b, x0 + int(i), y0 + int(j));
          mx += w * p;
          my += w * q;
          mxx += w * p * p;
          myy += w * q * q;
          mxy += w * p * q;
        }
      }
      const double c1 = 1e-4, c2 = 9e-4;
      total += (2 * mx * my + c1) * (2 * (mxy - mx * my) + c2) /
               ((mx * mx + my * my + c1) * (mxx - mx * mx + myy - my * my + c2));
      ++count;
    }
  }
  return total / count;
}

TEST(Ssim, IsExactlyOneForIdenticalImages) {
  const Image image = add_noise(test_pattern(48, 40), 0.05f, 1);
  EXPECT_EQ(ssim(image, image), 1.0);
}

TEST(Ssim, DropsAsNoiseGrows) {
  const Image reference = test_pattern(64, 48);
  const double light = ssim(add_noise(reference, 0.02f, 3), reference);
  const double heavy = ssim(add_noise(reference, 0.2f, 3), reference);
  EXPECT_LT(light, 1.0);
  EXPECT_LT(heavy, light);
  EXPECT_LT(heavy, 0.5);
  EXPECT_GT(light, 0.5);
}

TEST(Ssim, OfConstantImagesIsTheLuminanceTerm) {
  // No variance, so SSIM = (2 x y + C1) / (x^2 + y^2 + C1) on encoded greys.
  const Image a(20, 20, vec4(vec3(0.2f), 1.0f));
  const Image b(20, 20, vec4(vec3(0.5f), 1.0f));
  const double x = srgb_encode(0.2f);
  const double y = srgb_encode(0.5f);
  EXPECT_NEAR(ssim(a, b), (2 * x * y + 1e-4) / (x * x + y * y + 1e-4), 1e-6);
}

TEST(Ssim, MatchesADirectWindowedComputation) {
  for (const ivec2& size : {ivec2(23, 17), ivec2(11, 11), ivec2(40, 70), ivec2(8, 5), ivec2(1, 30)}) {
    const Image reference = test_pattern(size.x, size.y);
    const Image test = add_noise(reference, 0.1f, 11);
    EXPECT_NEAR(ssim(test, reference), brute_force_ssim(test, reference), 1e-9) << size.x << "x" << size.y;
    EXPECT_NEAR(ssim(test, reference), ssim(reference, test), 1e-12);
  }
}

TEST(ImageMetrics, CompareImagesGathersEveryMetric) {
  const Image reference = test_pattern(30, 20);
  const Image test = add_noise(reference, 0.05f, 5);
  const ImageComparison c = compare_images(test, reference);
  const DeltaEStats de = delta_e_stats(test, reference);
  EXPECT_DOUBLE_EQ(c.rmse, rmse(test, reference));
  EXPECT_DOUBLE_EQ(c.psnr, psnr(test, reference));
  EXPECT_DOUBLE_EQ(c.mae, mean_absolute_error(test, reference));
  EXPECT_DOUBLE_EQ(c.ssim, ssim(test, reference));
  EXPECT_DOUBLE_EQ(c.mean_de, de.mean);
  EXPECT_DOUBLE_EQ(c.median_de, de.median);
  EXPECT_DOUBLE_EQ(c.p99_de, de.p99);
  EXPECT_DOUBLE_EQ(c.max_de, de.max);
  EXPECT_GT(c.mean_de, 0.0);
  EXPECT_LE(c.p99_de, c.max_de);
}

}  // namespace
}  // namespace penumbra

// Ament et al. 2014, Fig. 4: the floor shadow of the chirp occluder,
// Fourier-analysed. Each frequency of a chirp sits at its own place along x,
// and filtering the optical depth there multiplies that frequency by the
// filter's transfer function, so the ratio of the filtered shadow's amplitude
// spectrum to the unfiltered one (shadow-rays) is |H(f)|: the sinc of the
// box, with its zero at f = 1 / w and the side lobe behind it, and the
// Gaussian's smooth decay.
#include "chirp_experiment.h"

#include <gtest/gtest.h>

#include <cstdio>

namespace penumbra {
namespace {

using namespace penumbra::testing;

// Filter width in voxels: the sinc's zeros at 255 / 20 = 12.8 and 25.5
// cycles, both inside the chirp's 1 to 32 cycles over its 256 voxels (the
// paper's "two deleted frequencies").
constexpr float kWidth = 20.0f;
constexpr int kLength = 256;

struct Spectra {
  std::vector<float> reference, box, gaussian;
};

Spectra chirp_spectra() {
  const Scene scene = chirp_scene(ivec3(kLength, 24, 24), 8);
  const ParameterSettings box = {{"filter_voxels", double(kWidth)}, {"shadow_cache", false}};
  ParameterSettings gaussian = box;
  gaussian["kernel"] = std::string("gaussian");
  return {windowed_spectrum(shadow_depth_profile(render_with(scene, "shadow-rays"))),
          windowed_spectrum(shadow_depth_profile(render_with(scene, "filtered-sat", box))),
          windowed_spectrum(shadow_depth_profile(render_with(scene, "filtered-sat", gaussian)))};
}

// Bins where the chirp has energy (1 to 32 cycles over the profile, above a
// fifth of its peak): the ratio is measured there only.
TEST(ChirpExperiment, BoxSuppressesTheSincZerosAndGaussianDampsSmoothly) {
  const Spectra s = chirp_spectra();
  const double n = kLength - 1.0;  // profile length in voxels
  float peak = 0.0f;
  for (std::size_t k = 1; k < s.reference.size(); ++k) peak = std::max(peak, s.reference[k]);
  int checked = 0;
  double box_at_zero = 1.0, box_at_second_zero = 1.0, box_side_lobe = 0.0, gaussian_beyond = 0.0;
  double previous_gaussian = 2.0;
  for (std::size_t k = 1; k < s.reference.size(); ++k) {
    if (s.reference[k] < 0.2f * peak) continue;
    const double f = double(k) / n;
    const double box = s.box[k] / s.reference[k];
    const double gaussian = s.gaussian[k] / s.reference[k];
    std::printf("bin %2zu f w %.2f  box %.3f (|sinc| %.3f)  gaussian %.3f (predicted %.3f)\n", k, f * kWidth, box,
                box_response(f, kWidth), gaussian, gaussian_response(f, kWidth));
    // The spectra of a finite, windowed chirp are not exactly local in
    // frequency (neighbouring bins mix over the Hann window's main lobe, +-2
    // bins, and the table's cells blur a little), so the ratio is held to
    // the prediction within 0.08 (observed: within 0.038 for the box, 0.055
    // for the Gaussian).
    EXPECT_NEAR(box, box_response(f, kWidth), 0.08) << "bin " << k;
    EXPECT_NEAR(gaussian, gaussian_response(f, kWidth), 0.08) << "bin " << k;
    EXPECT_LT(gaussian, previous_gaussian + 0.01) << "the Gaussian's damping only grows with f";
    previous_gaussian = gaussian;
    if (std::abs(f * kWidth - 1.0) < 0.1) box_at_zero = std::min(box_at_zero, box);
    if (std::abs(f * kWidth - 2.0) < 0.1) box_at_second_zero = std::min(box_at_second_zero, box);
    if (f * kWidth > 1.25 && f * kWidth < 1.75) {
      box_side_lobe = std::max(box_side_lobe, box);
      gaussian_beyond = std::max(gaussian_beyond, gaussian);
    }
    ++checked;
  }
  EXPECT_GE(checked, 20);  // observed 22 bins
  // The box erases the frequencies 1 / w and 2 / w (observed 0.032 and
  // 0.047) and lets the side lobe between them through (|sinc| rises to 0.22
  // at f w = 1.43); the Gaussian has no rebound.
  EXPECT_LT(box_at_zero, 0.08);
  EXPECT_LT(box_at_second_zero, 0.08);
  EXPECT_GT(box_side_lobe, 0.15);
  EXPECT_LT(gaussian_beyond, 0.1);
}

}  // namespace
}  // namespace penumbra

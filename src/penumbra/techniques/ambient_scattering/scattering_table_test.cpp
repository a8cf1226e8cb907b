// The preintegrated scattering of an ambient sphere against brute-force
// integrations that share nothing with the table's estimator: single
// scattering by quadrature, all orders by forward photon tracing.
#include "penumbra/base/error.h"
#include "penumbra/base/rng.h"
#include "penumbra/techniques/ambient_scattering/scattering_table.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace penumbra {
namespace {

constexpr double kBallPi = 3.14159265358979323846;

double ball_phase(double g, double cosine) {
  const double denom = 1.0 + g * g - 2.0 * g * cosine;
  return (1.0 - g * g) / (4.0 * kBallPi * denom * std::sqrt(denom));
}

// Light scattered exactly once inside the unit ball (beam along +z, unit
// irradiance, optical radius tau) and arriving at `point` travelling along
// w: the integral over the segment back to the ball's surface of
// tau e^(-tau s) a p(z . w) e^(-tau l(y)), l(y) the depth of y toward the
// light. Midpoint rule in s.
double once_scattered_radiance(double tau, double albedo, double g, glm::dvec3 point, glm::dvec3 w) {
  const double b = glm::dot(point, -w), c = glm::dot(point, point) - 1.0;
  const double length = -b + std::sqrt(std::max(0.0, b * b - c));
  constexpr int kSteps = 200;
  double sum = 0.0;
  for (int i = 0; i < kSteps; ++i) {
    const double s = (i + 0.5) * length / kSteps;
    const glm::dvec3 y = point - s * w;
    const double depth = y.z + std::sqrt(std::max(0.0, 1.0 - y.x * y.x - y.y * y.y));
    sum += tau * std::exp(-tau * s) * albedo * ball_phase(g, w.z) * std::exp(-tau * depth);
  }
  return sum * length / kSteps;
}

// Quadrature over the sphere of directions (polar angle from +z, azimuth)
// of weight(w) * once_scattered_radiance(w).
template <class Weight>
double over_directions(double tau, double albedo, double g, glm::dvec3 point, const Weight& weight,
                       bool forward_only) {
  constexpr int kPolar = 120, kAzimuth = 64;
  const double top = forward_only ? 0.5 * kBallPi : kBallPi;
  double sum = 0.0;
  for (int i = 0; i < kPolar; ++i) {
    const double theta = (i + 0.5) * top / kPolar;
    for (int j = 0; j < kAzimuth; ++j) {
      const double phi = (j + 0.5) * 2.0 * kBallPi / kAzimuth;
      const glm::dvec3 w(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
      sum += weight(w) * once_scattered_radiance(tau, albedo, g, point, w) * std::sin(theta);
    }
  }
  return sum * (top / kPolar) * (2.0 * kBallPi / kAzimuth);
}

// Single scattering inside the ball: the table's estimator limited to one
// scattering event against quadrature, for the in-scattering at the centre
// toward three view directions, and the forward irradiance at the exit pole
// (a tube step) and at the centre (a surface).
TEST(ScatteringTable, SingleScatteringMatchesQuadrature) {
  for (const double g : {0.0, 0.5}) {
    // The 1D columns take 8 times the paths of a node.
    const ScatteringModel once{0.6f, float(g), 120000, 1}, once_columns{0.6f, float(g), 10000, 1};
    for (const double tau : {0.5, 2.0}) {
      SCOPED_TRACE(::testing::Message() << "g " << g << " tau " << tau);
      for (const double mu : {1.0, 0.0, -0.7}) {
        const glm::dvec3 view(std::sqrt(1.0 - mu * mu), 0.0, mu);
        const double exact = over_directions(
                                 tau, 0.6, g, glm::dvec3(0.0),
                                 [&](glm::dvec3 w) { return ball_phase(g, glm::dot(w, view)); }, false) /
                             ball_phase(g, mu);
        const double table = scattered_in_scattering(once, tau, mu);
        std::printf("g %.1f tau %.1f mu %+.1f: J_s/p %.5f, quadrature %.5f\n", g, tau, mu, table, exact);
        EXPECT_NEAR(table, exact, 0.015 * exact + 1e-5) << "mu " << mu;
      }
      const auto cosine = [](glm::dvec3 w) { return w.z; };
      const double pole = over_directions(tau, 0.6, g, glm::dvec3(0.0, 0.0, 1.0), cosine, true);
      const double centre = over_directions(tau, 0.6, g, glm::dvec3(0.0), cosine, true);
      const double tube = scattered_tube_transfer(once_columns, tau);
      const double surface = scattered_surface_transfer(once_columns, tau);
      std::printf("g %.1f tau %.1f: F_s %.5f (%.5f), H_s %.5f (%.5f)\n", g, tau, tube, pole, surface, centre);
      EXPECT_NEAR(tube, pole, 0.01 * pole + 1e-5);
      EXPECT_NEAR(surface, centre, 0.01 * centre + 1e-5);
    }
  }
}

// All orders: forward photon tracing from the beam (photons enter at points
// spread uniformly over the ball's cross-section, free flights, absorption
// by weight, the same phase function), scoring the track length of scattered
// photons inside a small ball of radius r around the centre weighted by the
// phase toward the viewer: the mean in-scattering there. A different
// estimator from the table's backward paths; r = 0.12 biases it by well
// under 1 % here (the fields vary over tau r ~ 0.2).
double forward_in_scattering(double tau, double albedo, double g, double mu, int photons) {
  constexpr double kDetector = 0.12;
  const glm::dvec3 view(std::sqrt(1.0 - mu * mu), 0.0, mu);
  Pcg32 rng(7);
  auto uniform = [&] { return double(rng.next_float()); };
  double score = 0.0;
  for (int n = 0; n < photons; ++n) {
    const double r = std::sqrt(uniform()), phi = 2.0 * kBallPi * uniform();
    glm::dvec3 x(r * std::cos(phi), r * std::sin(phi), 0.0);
    x.z = -std::sqrt(std::max(0.0, 1.0 - x.x * x.x - x.y * x.y));
    glm::dvec3 d(0.0, 0.0, 1.0);
    double weight = 1.0;
    for (int event = 0; event < 100000; ++event) {
      const double b = glm::dot(x, d), c = glm::dot(x, x) - 1.0;
      const double boundary = -b + std::sqrt(std::max(0.0, b * b - c));
      const double flight = std::min(-std::log(1.0 - uniform()) / tau, boundary);
      if (event > 0) {
        // Track length of [x, x + flight d] inside the detector.
        const double bd = glm::dot(x, d), cd = glm::dot(x, x) - kDetector * kDetector;
        const double disc = bd * bd - cd;
        if (disc > 0.0) {
          const double t0 = std::max(0.0, -bd - std::sqrt(disc)), t1 = std::min(flight, -bd + std::sqrt(disc));
          if (t1 > t0) score += weight * (t1 - t0) * ball_phase(g, glm::dot(d, view));
        }
      }
      if (flight >= boundary) break;
      x += flight * d;
      weight *= albedo;
      if (weight < 1e-4) break;
      // New direction around d by the phase function.
      const double xi = uniform(), az = 2.0 * kBallPi * uniform();
      double cosine = 1.0 - 2.0 * xi;
      if (g != 0.0) {
        const double s = (1.0 - g * g) / (1.0 - g + 2.0 * g * xi);
        cosine = (1.0 + g * g - s * s) / (2.0 * g);
      }
      const glm::dvec3 axis = std::abs(d.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
      const glm::dvec3 u = glm::normalize(glm::cross(axis, d));
      const glm::dvec3 v = glm::cross(d, u);
      const double sine = std::sqrt(std::max(0.0, 1.0 - cosine * cosine));
      d = sine * std::cos(az) * u + sine * std::sin(az) * v + cosine * d;
    }
  }
  // Power pi enters (unit irradiance over the cross-section); the detector's
  // volume turns summed track length into mean radiance over directions.
  const double volume = 4.0 / 3.0 * kBallPi * kDetector * kDetector * kDetector;
  return score * (kBallPi / photons) / volume / ball_phase(g, mu);
}

TEST(ScatteringTable, AllOrdersMatchForwardPhotonTracing) {
  struct Case {
    double tau, g, mu;
  };
  for (const Case c : {Case{1.0, 0.0, 0.0}, Case{3.0, 0.0, 0.0}, Case{1.5, 0.5, 1.0}, Case{1.5, 0.5, -1.0}}) {
    const ScatteringModel model{0.8f, float(c.g), 20000};
    const double table = scattered_in_scattering(model, c.tau, c.mu);
    const double forward = forward_in_scattering(c.tau, 0.8, c.g, c.mu, 1500000);
    std::printf("tau %.1f g %.1f mu %+.1f: J_s/p backward %.5f, forward %.5f\n", c.tau, c.g, c.mu, table, forward);
    EXPECT_NEAR(table, forward, 0.04 * forward) << "tau " << c.tau << " g " << c.g << " mu " << c.mu;
  }
}

// The table at its nodes is the estimator plus the unscattered part; between
// nodes its bilinear interpolation stays within a few percent of the
// estimator there.
TEST(ScatteringTable, LookupsInterpolateTheEstimator) {
  const ScatteringModel model{0.6f, 0.3f, 256};
  const ScatteringTable table(model);
  const ScatteringTableView view = table.view();
  for (const int i : {3, 17, 30}) {
    const double tau = ScatteringTable::tau_at(i);
    for (const int j : {0, 9, 32}) {
      const double mu = ScatteringTable::cos_at(j);
      const double expected = std::exp(-tau) + scattered_in_scattering(model, tau, mu);
      EXPECT_NEAR(view.in_scattering<ScalarLanes>(float(tau), float(mu)), expected, 1e-4 + 1e-4 * expected);
    }
    EXPECT_NEAR(view.tube_transfer(float(tau)), std::exp(-2.0 * tau) + scattered_tube_transfer(model, tau), 1e-4);
    EXPECT_NEAR(view.surface_transfer(float(tau)), std::exp(-tau) + scattered_surface_transfer(model, tau), 1e-4);
  }
  for (const double tau : {0.3, 1.3, 4.7}) {
    for (const double mu : {0.83, 0.1, -0.55}) {
      const double expected = std::exp(-tau) + scattered_in_scattering(model, tau, mu);
      EXPECT_NEAR(view.in_scattering<ScalarLanes>(float(tau), float(mu)), expected, 0.03 * expected)
          << "tau " << tau << " mu " << mu;
    }
  }
  // Nothing scatters without albedo: the three are the exponentials.
  const ScatteringTable black(ScatteringModel{0.0f, 0.3f, 16});
  EXPECT_FLOAT_EQ(black.view().in_scattering<ScalarLanes>(1.7f, -0.3f), std::exp(-1.7f));
  EXPECT_FLOAT_EQ(black.view().tube_transfer(1.7f), std::exp(-3.4f));
}

TEST(ScatteringTable, BadModelsNameTheParameter) {
  try {
    ScatteringTable table(ScatteringModel{1.0f, 0.0f, 16});
    ADD_FAILURE() << "albedo 1 accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.name(), "scattering_albedo");
  }
  try {
    ScatteringTable table(ScatteringModel{0.5f, 1.0f, 16});
    ADD_FAILURE() << "g 1 accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.name(), "phase_g");
  }
}

}  // namespace
}  // namespace penumbra

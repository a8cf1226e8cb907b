#include "penumbra/techniques/ambient_scattering/scattering_table.h"

#include "penumbra/base/error.h"
#include "penumbra/base/parallel.h"
#include "penumbra/base/rng.h"

#include <cmath>
#include <deque>
#include <limits>
#include <mutex>

namespace penumbra {
namespace {

using glm::dvec3;

constexpr double kPi = 3.14159265358979323846;
const dvec3 kBeam(0.0, 0.0, 1.0);  // the direction the beam travels, d

// Henyey-Greenstein, normalised over the sphere.
double phase(double g, double cosine) {
  const double denom = 1.0 + g * g - 2.0 * g * cosine;
  return (1.0 - g * g) / (4.0 * kPi * denom * std::sqrt(denom));
}

// Distance from p (inside the unit ball or on it) to its surface along unit v.
double exit_distance(const dvec3& p, const dvec3& v) {
  const double b = glm::dot(p, v);
  const double c = glm::dot(p, p) - 1.0;
  return std::max(0.0, -b + std::sqrt(std::max(0.0, b * b - c)));
}

double uniform(Pcg32& rng) { return double(rng.next_float()); }

// Path k's generator: one stream, states spread by a hash (PCG streams that
// differ only in their increment are correlated).
Pcg32 path_generator(int k, std::uint64_t salt) {
  return Pcg32(0x9e3779b97f4a7c15ULL, mix_bits(std::uint64_t(k) * 2654435761ULL + salt));
}

// The unit vector at cosine `cosine` and azimuth `phi` around unit w, in the
// frame (u, v, w); u, v are any continuous completion of w.
dvec3 around(const dvec3& w, const dvec3& u, double cosine, double phi) {
  const dvec3 v = glm::cross(w, u);
  const double sine = std::sqrt(std::max(0.0, 1.0 - cosine * cosine));
  return sine * std::cos(phi) * u + sine * std::sin(phi) * v + cosine * w;
}

dvec3 any_perpendicular(const dvec3& w) {
  const dvec3 axis = std::abs(w.x) < 0.6 ? dvec3(1.0, 0.0, 0.0) : dvec3(0.0, 1.0, 0.0);
  return glm::normalize(glm::cross(axis, w));
}

// A direction drawn from the phase function around w (the cosine between
// the two) by the uniform numbers xi (cosine) and eta (azimuth), with u
// completing w's frame.
dvec3 sample_phase(double g, const dvec3& w, const dvec3& u, double xi, double eta) {
  const double phi = 2.0 * kPi * eta;
  double cosine;
  if (std::abs(g) < 1e-4) {
    cosine = 1.0 - 2.0 * xi;
  } else {
    const double s = (1.0 - g * g) / (1.0 - g + 2.0 * g * xi);
    cosine = std::clamp((1.0 + g * g - s * s) / (2.0 * g), -1.0, 1.0);
  }
  return around(w, u, cosine, phi);
}

dvec3 sample_phase(double g, const dvec3& w, const dvec3& u, Pcg32& rng) {
  const double xi = uniform(rng);
  return sample_phase(g, w, u, xi, uniform(rng));
}

// Path k's first three numbers: a Kronecker sequence (R3, with the powers
// of the generalised golden ratio), so the first direction and flight of
// the paths of a node spread evenly; the rest is random.
struct FirstNumbers {
  double direction[2];
  double flight;
};
FirstNumbers first_numbers(int k) {
  constexpr double kPhi3 = 1.2207440845961405;
  const double n = double(k) + 0.5;
  auto fraction = [](double x) { return x - std::floor(x); };
  return FirstNumbers{{fraction(n / kPhi3), fraction(n / (kPhi3 * kPhi3))}, fraction(n / (kPhi3 * kPhi3 * kPhi3))};
}

// The radiance travelling along `direction` that arrives at `start` from
// light scattered inside the ball at least once, for one backward path: its
// vertices are drawn by free flights back along the path and by the phase
// function, and each adds the beam's single scattering there (the beam
// reaches a point y attenuated by the ball's depth toward the light,
// e^-tau l(y)). Russian roulette ends paths of small weight.
// `first_flight` is the uniform number of the first free flight.
double scattered_radiance(const ScatteringModel& m, double sigma, dvec3 position, dvec3 direction, Pcg32& rng,
                          double first_flight) {
  if (!(sigma > 0.0) || m.albedo <= 0.0f) return 0.0;
  const double albedo = m.albedo, g = m.g;
  double weight = 1.0, total = 0.0;
  for (int event = 0; event < m.max_events; ++event) {
    const double boundary = exit_distance(position, -direction);
    const double flight = -std::log(1.0 - (event == 0 ? first_flight : uniform(rng))) / sigma;
    if (flight >= boundary) break;
    position -= flight * direction;
    weight *= albedo;
    total += weight * phase(g, glm::dot(kBeam, direction)) * std::exp(-sigma * exit_distance(position, -kBeam));
    direction = sample_phase(g, direction, any_perpendicular(direction), rng);
    if (weight < 0.05) {
      if (uniform(rng) >= 0.5) break;
      weight *= 2.0;
    }
  }
  return total;
}

// Forward irradiance of the scattered light at `point`: directions drawn
// with density (w . d) / pi over the forward hemisphere.
double scattered_forward_irradiance(const ScatteringModel& m, double tau, const dvec3& point, int paths) {
  const dvec3 u = any_perpendicular(kBeam);
  double sum = 0.0;
  for (int k = 0; k < paths; ++k) {
    Pcg32 rng = path_generator(k, 0x5851f42d4c957f2dULL);
    const FirstNumbers first = first_numbers(k);
    const double r2 = first.direction[0], phi = 2.0 * kPi * first.direction[1];
    const dvec3 direction = around(kBeam, u, std::sqrt(1.0 - r2), phi);
    sum += kPi * scattered_radiance(m, tau, point, direction, rng, first.flight);
  }
  return sum / paths;
}

void check(const ScatteringModel& m) {
  if (!(m.albedo >= 0.0f && m.albedo < 1.0f)) {
    throw InvalidArgument("scattering_albedo", "must lie in [0, 1)");
  }
  if (!(m.g > -1.0f && m.g < 1.0f)) throw InvalidArgument("phase_g", "must lie in (-1, 1)");
  if (m.paths < 1) throw InvalidArgument("preintegration_paths", "must be at least 1");
}

}  // namespace

double scattered_in_scattering(const ScatteringModel& m, double tau, double mu) {
  mu = std::clamp(mu, -1.0, 1.0);
  // The viewer's direction in the x-z plane; its frame's first axis is
  // continuous in mu, so neighbouring columns draw neighbouring paths.
  const dvec3 view(std::sqrt(std::max(0.0, 1.0 - mu * mu)), 0.0, mu);
  const dvec3 u = glm::cross(dvec3(0.0, 1.0, 0.0), view);
  double sum = 0.0;
  for (int k = 0; k < m.paths; ++k) {
    Pcg32 rng = path_generator(k, 0);
    const FirstNumbers first = first_numbers(k);
    const dvec3 direction = sample_phase(m.g, view, u, first.direction[0], first.direction[1]);
    sum += scattered_radiance(m, tau, dvec3(0.0), direction, rng, first.flight);
  }
  return sum / m.paths / phase(m.g, mu);
}

double scattered_tube_transfer(const ScatteringModel& m, double tau) {
  return scattered_forward_irradiance(m, tau, kBeam, 8 * m.paths);
}

double scattered_surface_transfer(const ScatteringModel& m, double tau) {
  return scattered_forward_irradiance(m, tau, dvec3(0.0), 8 * m.paths);
}

double ScatteringTable::tau_at(int i) {
  if (i >= kTauCount - 1) return std::numeric_limits<double>::infinity();
  const double u = double(i) / double(kTauCount - 1);
  return ScatteringTableView::kTauScale * u / (1.0 - u);
}

double ScatteringTable::cos_at(int j) {
  const double s = double(j) / double(kCosCount - 1);
  return 1.0 - 2.0 * s * s;
}

ScatteringTable::ScatteringTable(const ScatteringModel& model) : model_(model) {
  check(model);
  values_.assign(std::size_t(kTauCount) * (kCosCount + 2), 0.0f);
  float* in = values_.data();
  float* tube = in + std::size_t(kTauCount) * kCosCount;
  float* surface = tube + kTauCount;
  // Row 0 (tau = 0) scatters nothing, the last (tau = inf) lets nothing in.
  parallel_for(1, kTauCount - 1, [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t i = first; i < last; ++i) {
      const double tau = tau_at(int(i));
      for (int j = 0; j < kCosCount; ++j) {
        in[i * kCosCount + j] = float(scattered_in_scattering(model_, tau, cos_at(j)));
      }
      tube[i] = float(scattered_tube_transfer(model_, tau));
      surface[i] = float(scattered_surface_transfer(model_, tau));
    }
  });
}

std::shared_ptr<const ScatteringTable> preintegrated_scattering(const ScatteringModel& model) {
  static std::mutex mutex;
  static std::deque<std::shared_ptr<const ScatteringTable>> tables;
  constexpr std::size_t kKept = 4;
  {
    std::lock_guard<std::mutex> lock(mutex);
    for (const auto& t : tables) {
      if (t->model() == model) return t;
    }
  }
  auto table = std::make_shared<const ScatteringTable>(model);
  std::lock_guard<std::mutex> lock(mutex);
  tables.push_front(table);
  if (tables.size() > kKept) tables.pop_back();
  return table;
}

}  // namespace penumbra

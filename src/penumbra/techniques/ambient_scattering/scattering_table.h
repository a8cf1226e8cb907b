#pragma once
// The preintegrated scattering of one ambient sphere (ambient_scattering.h):
// a homogeneous ball of radius 1 with optical radius tau (= sigma R), a grey
// scattering albedo a and the Henyey-Greenstein phase function of asymmetry
// g, lit by a collimated beam of unit irradiance travelling along d. For
// each tau the table holds what light scattered inside the ball adds to
// three quantities whose unscattered part the kernels compute exactly:
//
//   M(tau, mu)  in-scattering at the centre toward a viewer at cosine mu to d
//               (J = integral of p(w . view) L(centre, w) dw), over the
//               single-scattering phase p(mu):  M = e^-tau + J_s / p(mu)
//   F(tau)      forward irradiance where the beam's axis leaves the ball,
//               integral over w . d > 0 of L(w) (w . d) dw: the light one
//               tube step passes on to the next sphere:  F = e^-2tau + F_s
//   H(tau)      the same at the centre, for a surface point (a floor) whose
//               own sphere is lit:  H = e^-tau + H_s
//
// With a = 0 the scattered parts are 0 and the three are exact
// exponentials. The scattered parts are integrated by backward Monte Carlo
// paths with next-event estimation to the beam (scattering_table.cpp), their
// first direction and flight from a low-discrepancy sequence, every node with
// the same numbers, so the table is smooth along both axes. Rows are uniform
// in u = tau / (tau + 2) (the last row is tau = inf, where nothing arrives),
// columns uniform in s = sqrt((1 - mu) / 2) = sin of half the angle, so the
// forward lobe of a large g has as many columns as the backward half.
#include "penumbra/base/math.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace penumbra {

struct ScatteringTableView {
  static constexpr float kTauScale = 2.0f;
  // tau_count * cos_count values of J_s / p, then tau_count of F_s, then
  // tau_count of H_s.
  const float* values = nullptr;
  int tau_count = 0;
  int cos_count = 0;

  template <class Mirror> ScatteringTableView on_device(Mirror& m) const {
    ScatteringTableView d = *this;
    d.values = m.structure(values, std::size_t(tau_count) * std::size_t(cos_count + 2), "the scattering table");
    return d;
  }

  // Row coordinate of an optical radius (>= 0), in [0, tau_count - 1].
  template <class F> PENUMBRA_HD PENUMBRA_FORCE_INLINE F row(F tau) const {
    const F x = tau / (tau + kTauScale) * float(tau_count - 1);
    return min(x, F(float(tau_count - 1)));
  }

  // M(tau, mu) for one sample or a packet (base/lanes.h).
  template <class L>
  PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Float in_scattering(typename L::Float tau,
                                                                    typename L::Float mu) const {
    using F = typename L::Float;
    using I = typename L::Int;
    using X = typename L::Index;
    tau = max(tau, F(0.0f));
    const F x = row(tau);
    I i = to_int_nonnegative(x);
    i = select(i > I(tau_count - 2), I(tau_count - 2), i);
    const F fx = x - to_float(i);
    const F half = max(F(0.0f), (1.0f - mu) * 0.5f);
    const F y = min(sqrt(half) * float(cos_count - 1), F(float(cos_count - 1)));
    I j = to_int_nonnegative(y);
    j = select(j > I(cos_count - 2), I(cos_count - 2), j);
    const F fy = y - to_float(j);
    const X at = X(i) * cos_count + X(j);
    const F v00 = gather(values, at), v01 = gather(values + 1, at);
    const F v10 = gather(values + cos_count, at), v11 = gather(values + cos_count + 1, at);
    const F near_row = v00 + fy * (v01 - v00);
    const F far_row = v10 + fy * (v11 - v10);
    return exp_nonpositive(-tau) + near_row + fx * (far_row - near_row);
  }

  // F(tau) and H(tau) (scalar: the tube march and the surface lookups).
  PENUMBRA_HD float tube_transfer(float tau) const {
    tau = glm::max(tau, 0.0f);
    return exp_nonpositive(-2.0f * tau) + column(std::size_t(tau_count) * std::size_t(cos_count), tau);
  }
  PENUMBRA_HD float surface_transfer(float tau) const {
    tau = glm::max(tau, 0.0f);
    return exp_nonpositive(-tau) + column(std::size_t(tau_count) * std::size_t(cos_count + 1), tau);
  }

 private:
  PENUMBRA_HD float column(std::size_t first, float tau) const {
    const float x = row(tau);
    const int i = glm::min(int(x), tau_count - 2);
    const float* v = values + first + i;
    return v[0] + (x - float(i)) * (v[1] - v[0]);
  }
};

// The ball's parameters and how the scattered parts are integrated.
struct ScatteringModel {
  float albedo = 0.6f;
  float g = 0.0f;
  int paths = 512;  // per node (the 1D columns take 8 times as many)
  // Scattering events inside the ball a path may have before the light
  // reaches the centre (or exit point): 1 keeps single scattering inside
  // the ball only (tests compare that order against quadrature); the
  // default is all orders.
  int max_events = 1 << 20;
  bool operator==(const ScatteringModel&) const = default;
};

class ScatteringTable {
 public:
  static constexpr int kTauCount = 48;
  static constexpr int kCosCount = 33;

  // Integrates the table (a few hundred milliseconds at the default paths;
  // parallel over rows). Throws InvalidArgument naming "scattering_albedo"
  // for an albedo outside [0, 1) and "phase_g" outside (-1, 1).
  explicit ScatteringTable(const ScatteringModel& model);

  const ScatteringModel& model() const { return model_; }
  ScatteringTableView view() const {
    return ScatteringTableView{values_.data(), kTauCount, kCosCount};
  }
  std::uint64_t bytes() const { return values_.size() * sizeof(float); }

  // The node positions: row i's optical radius (+inf for the last) and
  // column j's cosine.
  static double tau_at(int i);
  static double cos_at(int j);

 private:
  ScatteringModel model_;
  std::vector<float> values_;
};

// The scattered parts at one point of the table's domain, by the table's own
// estimator (for tests and for the table): J_s / p(mu), F_s and H_s.
double scattered_in_scattering(const ScatteringModel& model, double tau, double mu);
double scattered_tube_transfer(const ScatteringModel& model, double tau);
double scattered_surface_transfer(const ScatteringModel& model, double tau);

// The table for `model`, integrated once per process and model (the paper
// precomputes its tables offline; they depend on neither data nor transfer
// function). Keeps the last few models.
std::shared_ptr<const ScatteringTable> preintegrated_scattering(const ScatteringModel& model);

}  // namespace penumbra

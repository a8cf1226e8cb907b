#pragma once
// The occluded fraction of a region from its moments: the share of its
// voxels whose value is at least the query t.
//
// Two moments (Penner & Mitchell 2008, eq. 12, after Donnelly & Lauritzen's
// variance shadow maps): Chebyshev's one-sided (Cantelli) inequality
//   P(X >= t) <= p_max(t) = sigma^2 / (sigma^2 + (t - mu)^2) for t > mu, else 1.
// The paper writes the left side as P(x <= t), in variance shadow mapping's
// convention where the texels beyond the receiver are the lit ones; in a
// volume the voxels above the query occlude (eq. 5), and p_max is the bound
// on the occluded fraction, which is what the paper's bimodal argument uses
// (section 3.4: querying with d2 gives the fraction of d2, the occluders).
// For a region holding two values d1 < d2 it is exact at t = d2.
//
// Four moments (the paper's conclusion asks for a better CDF): the sharp
// upper bound on P(X >= t) given E[X^1..4], from the canonical representation
// of the moments through t (Markov-Krein; the same construction as the
// Hamburger four-moment shadow maps of Peters & Klein 2015): solve
// H c = (1, t, t^2) with the Hankel matrix H of the moments; the weight at t
// is 1 / K(t, t) = 1 / |L^-1 (1, t, t^2)|^2 (L: H's Cholesky factor), the
// other two support points are the roots of c2 z^2 + c1 z + c0, their weights
// match the first moment, and the bound adds the weights at or above t. It is
// never above the two-moment bound (more moments admit fewer distributions,
// so the sharp bound can only fall) and exact at every support point of a distribution with
// at most three values. The result is clamped to the two-moment bound, which
// only matters where rounding makes the four-moment reconstruction unreliable.
#include "penumbra/base/lanes.h"
#include "penumbra/base/math.h"

namespace penumbra {

// Floor of the variance: below it float rounding of the stored moments
// (about 1e-8 for u near 1) is all there is.
inline constexpr float kMinMomentVariance = 1e-7f;
// Bias of four moments toward those of the uniform distribution on [0, 1]
// (1/2, 1/3, 1/4, 1/5), which keeps the Hankel matrix positive definite under
// float rounding. It adds about kMomentBias / 12 to the variance, which moves
// a bound noticeably only for regions of almost one value.
inline constexpr double kMomentBias = 2e-5;

// Chebyshev's one-sided bound on the share above t of values with mean m1
// and second moment m2, on one lane (float) or a packet (base/lanes.h).
template <class F> PENUMBRA_HD PENUMBRA_FORCE_INLINE F chebyshev_occlusion_lanes(F m1, F m2, F t) {
  const F variance = max(m2 - m1 * m1, F(kMinMomentVariance));
  const F d = t - m1;
  return select(t <= m1, F(1.0f), variance / (variance + d * d));
}
PENUMBRA_HD inline float chebyshev_occlusion(float m1, float m2, float t) {
  return chebyshev_occlusion_lanes<float>(m1, m2, t);
}

PENUMBRA_HD inline float hamburger_occlusion(vec4 moments, float t) {
  const double a = kMomentBias;
  const double b1 = (1.0 - a) * moments.x + a / 2.0;
  const double b2 = (1.0 - a) * moments.y + a / 3.0;
  const double b3 = (1.0 - a) * moments.z + a / 4.0;
  const double b4 = (1.0 - a) * moments.w + a / 5.0;
  // Cholesky factor of H = [[1, b1, b2], [b1, b2, b3], [b2, b3, b4]]; its first column is (1, b1, b2).
  const double d22 = b2 - b1 * b1;
  if (!(d22 > 1e-14)) return chebyshev_occlusion(float(b1), float(b2), t);
  const double l22 = glm::sqrt(d22);
  const double l32 = (b3 - b1 * b2) / l22;
  const double d33 = b4 - b2 * b2 - l32 * l32;
  if (!(d33 > 1e-18)) return chebyshev_occlusion(float(b1), float(b2), t);
  const double l33 = glm::sqrt(d33);
  const double q = double(t);
  // y = L^-1 (1, t, t^2), c = L^-T y.
  const double y2 = (q - b1) / l22;
  const double y3 = (q * q - b2 - l32 * y2) / l33;
  const double c2 = y3 / l33;
  const double c1 = (y2 - l32 * c2) / l22;
  const double c0 = 1.0 - b1 * c1 - b2 * c2;
  const double w_t = 1.0 / (1.0 + y2 * y2 + y3 * y3);
  // The other support points: roots of c2 z^2 + c1 z + c0.
  double z2, z3;
  if (glm::abs(c2) < 1e-12 * (glm::abs(c1) + glm::abs(c0))) {
    z2 = z3 = -c0 / c1;
  } else {
    const double disc = glm::max(c1 * c1 - 4.0 * c2 * c0, 0.0);
    const double h = -0.5 * (c1 + (c1 >= 0.0 ? glm::sqrt(disc) : -glm::sqrt(disc)));
    z2 = h / c2;
    z3 = h != 0.0 ? c0 / h : z2;
  }
  // Their weights from the zeroth and first moments.
  const double rest0 = 1.0 - w_t, rest1 = b1 - w_t * q;
  double w2 = rest0, w3 = 0.0;
  if (glm::abs(z3 - z2) > 1e-12) {
    w3 = (rest1 - rest0 * z2) / (z3 - z2);
    w2 = rest0 - w3;
  }
  const double bound = w_t + (z2 > q ? w2 : 0.0) + (z3 > q ? w3 : 0.0);
  // Both are upper bounds, so their minimum is one too; it guards the nearly
  // singular case (two-valued regions, where float rounding of the moments is
  // as large as the bias) in which the reconstruction above loses accuracy.
  return glm::min(float(glm::clamp(bound, 0.0, 1.0)), chebyshev_occlusion(float(b1), float(b2), t));
}

// The occluded fraction bound for K moments of u (K = 2 or 4).
template <int K> PENUMBRA_HD float occluded_fraction(const glm::vec<K, float, glm::defaultp>& m, float t) {
  if constexpr (K == 2) {
    return chebyshev_occlusion(m.x, m.y, t);
  } else {
    return hamburger_occlusion(m, t);
  }
}

}  // namespace penumbra

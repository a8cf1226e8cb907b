#pragma once
// The specular term Patel et al. 2013 add where a viewing ray crosses a mesh
// surface (section 4.2, step 3; they cite Ashikmin, Premoze and Shirley's
// microfacet BRDF generator). penumbra uses the common Cook-Torrance form of
// that family,
//   f_s = D(h) G(v, l) F(v . h) / (4 (n . v) (n . l)),
// with the GGX distribution D (Walter et al. 2007, "Microfacet Models for
// Refraction through Rough Surfaces", eq. 33), the separable Smith shadowing
// G = G1(v) G1(l) for GGX (eq. 34) and Schlick's Fresnel approximation
// F = F0 + (1 - F0)(1 - v . h)^5. The shaded radiance uses the same
// convention as opaque planes (lighting.h: a white Lambertian plane gives
// cos * L), so it is pi f_s cos(theta_l) L.
#include "penumbra/base/math.h"

namespace penumbra {

PENUMBRA_HD inline float ggx_distribution(float n_dot_h, float alpha) {
  const float a2 = alpha * alpha;
  const float d = n_dot_h * n_dot_h * (a2 - 1.0f) + 1.0f;
  return a2 / (kPi * d * d);
}

PENUMBRA_HD inline float ggx_smith_g1(float n_dot_x, float alpha) {
  const float a2 = alpha * alpha;
  return 2.0f * n_dot_x / (n_dot_x + glm::sqrt(a2 + (1.0f - a2) * n_dot_x * n_dot_x));
}

// pi f_s (n . l): multiply by the light's radiance L. n, to_viewer and
// to_light are unit vectors; 0 when either lies below the surface.
PENUMBRA_HD inline float microfacet_specular(vec3 n, vec3 to_viewer, vec3 to_light, float f0, float alpha) {
  const float n_v = glm::dot(n, to_viewer), n_l = glm::dot(n, to_light);
  if (n_v <= 0.0f || n_l <= 0.0f || f0 <= 0.0f) return 0.0f;
  const vec3 h = glm::normalize(to_viewer + to_light);
  const float n_h = glm::max(glm::dot(n, h), 0.0f);
  const float v_h = glm::max(glm::dot(to_viewer, h), 0.0f);
  const float m = 1.0f - v_h;
  const float fresnel = f0 + (1.0f - f0) * (m * m) * (m * m) * m;
  const float f_s = ggx_distribution(n_h, alpha) * ggx_smith_g1(n_v, alpha) * ggx_smith_g1(n_l, alpha) * fresnel /
                    (4.0f * n_v * n_l);
  return kPi * f_s * n_l;
}

}  // namespace penumbra

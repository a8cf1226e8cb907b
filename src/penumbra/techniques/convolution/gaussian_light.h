#pragma once
// The Gaussian light of Patel et al. 2013 (section 3) on the virtual light
// plane, which penumbra places parallel to the slabs (perpendicular to the
// camera's forward axis f, with the camera's right r and up u as x and y):
// a light direction d (the way light travels) has the mean
//   mu = (d . r, d . u) / (d . f)          (= tan of the x- and y-tilt angles)
// and the covariance Sigma = R(alpha) diag(sigma_x^2, sigma_y^2) R(alpha)^T.
// The slab kernel for slab distance e and optimal distance d1 (eq. 7/15) has
// mean e mu (the lateral way light travels over one slab; the paper writes
// -e mu_l for the light's position, which lies opposite) and covariance
// d1 e Sigma.
//
// Mapping from the scene's lights (unless the technique's light_sigma_x2 /
// light_sigma_y2 / light_rotation_deg override the covariance for all lights):
//   distant, profile gaussian: directions normalize(c + x a + y b) with
//     (a, b) the light frame (distant_light_frame in light.h, rotation
//     included) and x ~ N(0, tan(angle_deg)^2), y ~ N(0, tan(angle_y_deg)^2)
//     independent; Sigma is that covariance carried to the slab plane by the
//     Jacobian J of d -> mu at c: Sigma = J diag(tx^2, ty^2) J^T, J's columns
//     the images of a and b (exact to first order; equal to
//     R diag(tx^2, ty^2) R^T when c = -f and the unrotated frame is the
//     camera's (right, up), R the rotation by rotation_deg);
//   distant, profile uniform: the cone's disk of radius tan(angle) has
//     variance tan(angle)^2 / 4 per axis, carried the same way;
//   directional: Sigma = 0 (hard shadows);
//   point, sphere, disk: a distant light from the light's position toward
//     the box centre (the method has only distant lights); a point light is
//     directional (Sigma = 0; one in front of every slab diverges instead,
//     through its own slab map: slab_renderer.cpp), a sphere or disk of radius r at distance D
//     from the box centre the uniform cone of the angle it subtends there,
//     tan = r / sqrt(D^2 - r^2) (the box centre as the one representative
//     receiver: the method's light is the same for every slab and pixel);
//   environment: no buffer (they carry no radiance in the shared shading).
// Lights must come from behind the viewer: a light more than 85 degrees from
// the view direction is clamped to 85 degrees (the method cannot represent it);
// the light frame is then that of the clamped direction.
#include "penumbra/base/math.h"
#include "penumbra/scene/camera.h"
#include "penumbra/scene/light.h"

#include <glm/mat2x2.hpp>

namespace penumbra {

struct GaussianLight {
  vec2 mu{0.0f};             // lateral travel per unit depth, camera (right, up)
  glm::mat2 covariance{0.0f};  // on the virtual light plane (units of mu^2)
  float cos_view = 1.0f;     // d . f: slab thickness e is crossed over e / cos_view
};

// sigma_x2 < 0: take the covariance from the scene light.
struct LightOverride {
  float sigma_x2 = -1.0f;
  float sigma_y2 = -1.0f;
  float rotation_deg = 0.0f;
};

GaussianLight gaussian_light(const Light& light, const CameraView& camera, vec3 box_center,
                             const LightOverride& override_sigma);

// Sigma = R(alpha) diag(sx2, sy2) R(alpha)^T.
glm::mat2 rotated_covariance(float sigma_x2, float sigma_y2, float rotation_deg);

// Eigen-decomposition of a symmetric 2x2 matrix: variances along its own axes
// (x = first, y = second) and the angle of the first axis from camera right.
struct PrincipalAxes {
  float var_x = 0.0f, var_y = 0.0f;
  float angle = 0.0f;  // radians
};
PrincipalAxes principal_axes(const glm::mat2& covariance);

}  // namespace penumbra

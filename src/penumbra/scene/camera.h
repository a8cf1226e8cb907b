#pragma once
// Camera: eye / target / up with a perspective (vertical fov) or orthographic
// (view height in world units) projection. CameraView is the plain struct the
// ray generator reads.
#include "penumbra/base/math.h"
#include "penumbra/base/ray.h"

namespace penumbra {

enum class Projection { Perspective, Orthographic };

// Precomputed frame for primary rays. Pixel (x, y) has its centre at
// (x + 0.5, y + 0.5); y grows downward in the image.
struct CameraView {
  vec3 eye{0.0f};
  vec3 forward{0.0f, 0.0f, -1.0f};
  vec3 right{1.0f, 0.0f, 0.0f};
  vec3 up{0.0f, 1.0f, 0.0f};
  float half_height = 1.0f;  // tan(fov / 2) for perspective, world half height for orthographic
  bool orthographic = false;

  // Ray through the image point (u, v) in [-1, 1] (u to the right, v up),
  // for an image of the given aspect (width / height).
  PENUMBRA_HD Ray ray(float u, float v, float aspect) const {
    const float sx = u * half_height * aspect;
    const float sy = v * half_height;
    if (orthographic) return Ray{eye + sx * right + sy * up, forward};
    return Ray{eye, glm::normalize(forward + sx * right + sy * up)};
  }

  PENUMBRA_HD Ray pixel_ray(float px, float py, int width, int height) const {
    const float u = 2.0f * px / float(width) - 1.0f;
    const float v = 1.0f - 2.0f * py / float(height);
    return ray(u, v, float(width) / float(height));
  }
};

struct Camera {
  vec3 eye{0.0f, -3.0f, 1.0f};
  vec3 target{0.0f};
  vec3 up{0.0f, 0.0f, 1.0f};
  float fov_deg = 30.0f;
  Projection projection = Projection::Perspective;
  float ortho_height = 2.0f;  // world-space height of the view (orthographic only)

  // Throws InvalidScene naming the field for a degenerate camera: eye ==
  // target, up parallel to the view direction, fov outside (0, 180), or a
  // non-positive ortho height.
  void validate() const;
  CameraView view() const;

  // Rotates the eye about the target: azimuth around `up`, elevation toward
  // it (clamped short of the pole so the frame stays defined).
  void orbit(float azimuth_deg, float elevation_deg);

  // A camera looking at the box centre from `direction` (pointing from the
  // target to the eye), far enough that the whole box fits the fov.
  static Camera framing(const Box3& box, vec3 direction = vec3(0.6f, -1.0f, 0.45f), vec3 up = vec3(0.0f, 0.0f, 1.0f),
                        float fov_deg = 30.0f);
};

}  // namespace penumbra

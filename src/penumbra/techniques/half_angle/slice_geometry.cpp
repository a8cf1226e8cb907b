#include "penumbra/techniques/half_angle/slice_geometry.h"

#include <cmath>

namespace penumbra {
namespace {

// Bounds the automatic slice count (a huge box with a tiny step).
constexpr int kMaxAutoSlices = 16384;

}  // namespace

SliceSetup make_slice_setup(const CameraView& camera, const Light& light, const Box3& box, int slices, float step) {
  SliceSetup setup;
  const vec3 v = camera.forward;
  vec3 l = light.at_infinity() ? light.direction : box.center() - light.position;
  l = glm::length(l) > 0.0f ? glm::normalize(l) : v;  // a light at the box centre: treat as a headlight
  setup.light_travel = l;
  setup.eye_front_to_back = glm::dot(v, l) >= 0.0f;
  const vec3 h = setup.eye_front_to_back ? v + l : l - v;
  setup.axis = glm::length(h) > 1e-6f ? glm::normalize(h) : v;
  float lo = kInfinity, hi = -kInfinity;
  for (int i = 0; i < 8; ++i) {
    const vec3 c(i & 1 ? box.upper.x : box.lower.x, i & 2 ? box.upper.y : box.lower.y,
                 i & 4 ? box.upper.z : box.lower.z);
    lo = glm::min(lo, glm::dot(setup.axis, c));
    hi = glm::max(hi, glm::dot(setup.axis, c));
  }
  const float extent = glm::max(hi - lo, 1e-6f);
  if (slices > 0) {
    setup.count = slices;
  } else {
    const float spacing = glm::max(step * glm::abs(glm::dot(v, setup.axis)), 1e-6f);
    setup.count = int(std::min(std::ceil(extent / spacing), float(kMaxAutoSlices)));
  }
  setup.spacing = extent / float(setup.count);
  setup.first = lo + 0.5f * setup.spacing;
  return setup;
}

int slice_polygon(const Box3& box, vec3 axis, float position, vec3 out[12]) {
  auto corner = [&](int i) {
    return vec3(i & 1 ? box.upper.x : box.lower.x, i & 2 ? box.upper.y : box.lower.y, i & 4 ? box.upper.z : box.lower.z);
  };
  int n = 0;
  for (int a = 0; a < 8; ++a) {
    for (int bit = 1; bit < 8; bit <<= 1) {
      if (a & bit) continue;  // each edge once, from its lower corner
      const vec3 p = corner(a), q = corner(a | bit);
      const float dp = glm::dot(axis, p) - position, dq = glm::dot(axis, q) - position;
      if ((dp < 0.0f) == (dq < 0.0f) && dp != 0.0f) continue;
      out[n++] = dp == dq ? p : p + (q - p) * (dp / (dp - dq));
    }
  }
  return n;
}

}  // namespace penumbra

#include "penumbra/techniques/sat_common/plane_caches.h"

#include <algorithm>
#include <cmath>

namespace penumbra {

PlaneCacheView PlaneCaches::layout(const Light& light, const Plane& plane, const Box3& box, float cell) {
  PlaneCacheView none;
  if (light.type == LightType::Environment || !(cell > 0.0f)) return none;
  const vec3 n = plane.normal, p0 = plane.point;
  const vec3 a = glm::normalize(glm::cross(n, std::abs(n.x) < 0.9f ? vec3(1, 0, 0) : vec3(0, 1, 0)));
  const vec3 b = glm::cross(n, a);
  vec2 lo(kInfinity), hi(-kInfinity);
  for (int corner = 0; corner < 8; ++corner) {
    const vec3 c((corner & 1) ? box.upper.x : box.lower.x, (corner & 2) ? box.upper.y : box.lower.y,
                 (corner & 4) ? box.upper.z : box.lower.z);
    const float hc = glm::dot(c - p0, n);
    vec3 q;
    if (light.at_infinity()) {
      const vec3 to_light = -glm::normalize(light.direction);
      const float denom = glm::dot(to_light, n);
      if (std::abs(denom) < 1e-3f) return none;  // grazing: the shadow stretches without bound
      q = c - to_light * (hc / denom);
    } else {
      const float hl = glm::dot(light.position - p0, n);
      // The whole box must lie between the light's height and the plane's far side.
      if (hl == 0.0f || hc / hl >= 0.999f) return none;
      q = light.position + (c - light.position) * (hl / (hl - hc));
    }
    const vec2 w(glm::dot(q - p0, a), glm::dot(q - p0, b));
    lo = glm::min(lo, w);
    hi = glm::max(hi, w);
  }
  lo -= vec2(cell);
  hi += vec2(cell);
  PlaneCacheView c;
  vec2 spacing;
  for (int k = 0; k < 2; ++k) {
    const float extent = hi[k] - lo[k];
    const double nodes = std::ceil(double(extent) / double(cell)) + 1.0;
    if (!(nodes <= double(kMaxSide))) return none;  // a grazing light: the march per point, as without a grid
    c.dims[k] = std::max(int(nodes), 2);
    spacing[k] = extent / float(c.dims[k] - 1);
  }
  c.origin = p0 + a * lo.x + b * lo.y;
  c.u = a / spacing.x;
  c.v = b / spacing.y;
  return c;
}

std::vector<vec4> PlaneCaches::key(const std::vector<Light>& lights, const std::vector<Plane>& planes, float cell) {
  std::vector<vec4> key;
  for (const Plane& p : planes) {
    key.push_back(vec4(p.point, 0.0f));
    key.push_back(vec4(p.normal, 0.0f));
  }
  for (const Light& l : lights) {
    key.push_back(vec4(l.position, float(l.type)));
    key.push_back(vec4(l.direction, cell));
  }
  return key;
}

void PlaneCaches::clear() {
  views_.clear();
  texels_.clear();
  key_.clear();
  version_ = ~std::uint64_t(0);
  plane_count_ = light_count_ = 0;
}

PlaneCachesView PlaneCaches::view() const {
  if (views_.empty()) return {};
  return PlaneCachesView{views_.data(), texels_.data(), plane_count_, light_count_};
}

}  // namespace penumbra

#include "penumbra/techniques/ipsvi/cache_fit.h"

#include <array>
#include <vector>

namespace penumbra {
namespace {

// Half-space dot(n, x) + d >= 0.
using HalfSpace = vec4;

// The camera's frustum: four sides through the image border and the plane
// through the eye across the view (nothing behind the camera is seen).
std::array<HalfSpace, 5> frustum(const CameraView& camera, float aspect) {
  const Ray r[4] = {camera.ray(-1.0f, -1.0f, aspect), camera.ray(1.0f, -1.0f, aspect), camera.ray(1.0f, 1.0f, aspect),
                    camera.ray(-1.0f, 1.0f, aspect)};
  const vec3 inside = camera.ray(0.0f, 0.0f, aspect).at(1.0f);
  std::array<HalfSpace, 5> sides;
  for (int i = 0; i < 4; ++i) {
    const Ray& a = r[i];
    const Ray& b = r[(i + 1) % 4];
    vec3 n = glm::cross(a.direction, b.origin + b.direction - a.origin);
    float d = -glm::dot(n, a.origin);
    if (glm::dot(n, inside) + d < 0.0f) {
      n = -n;
      d = -d;
    }
    sides[i] = HalfSpace(n, d);
  }
  sides[4] = HalfSpace(camera.forward, -glm::dot(camera.forward, camera.eye));
  return sides;
}

// Sutherland-Hodgman: the convex polygon clipped to the half-space.
std::vector<vec3> clip(const std::vector<vec3>& polygon, const HalfSpace& h) {
  std::vector<vec3> out;
  const std::size_t n = polygon.size();
  for (std::size_t i = 0; i < n; ++i) {
    const vec3& a = polygon[i];
    const vec3& b = polygon[(i + 1) % n];
    const float da = glm::dot(vec3(h), a) + h.w, db = glm::dot(vec3(h), b) + h.w;
    if (da >= 0.0f) out.push_back(a);
    if ((da >= 0.0f) != (db >= 0.0f)) out.push_back(a + (da / (da - db)) * (b - a));
  }
  return out;
}

void add_clipped(std::vector<vec3> polygon, const std::array<HalfSpace, 5>& sides, std::vector<vec3>& points) {
  for (const HalfSpace& h : sides) {
    polygon = clip(polygon, h);
    if (polygon.empty()) return;
  }
  points.insert(points.end(), polygon.begin(), polygon.end());
}

}  // namespace

LightCacheRegion visible_cache_region(const CameraView& camera, int width, int height, const Box3& box,
                                      const Plane* planes, int plane_count) {
  const float aspect = float(width) / float(glm::max(height, 1));
  const auto sides = frustum(camera, aspect);
  LightCacheRegion region;
  region.long_direction = camera.forward;
  region.bounds.assign(sides.begin(), sides.end());
  for (int axis = 0; axis < 3; ++axis) {
    vec4 lower(0.0f), upper(0.0f);
    lower[axis] = 1.0f;
    lower.w = -box.lower[axis];
    upper[axis] = -1.0f;
    upper.w = box.upper[axis];
    region.bounds.push_back(lower);
    region.bounds.push_back(upper);
  }
  // Every vertex of box-and-frustum lies on a box face, except the eye when
  // it is inside the box.
  const vec3 lo = box.lower, hi = box.upper;
  for (int axis = 0; axis < 3; ++axis) {
    const int a = (axis + 1) % 3, b = (axis + 2) % 3;
    for (int side = 0; side < 2; ++side) {
      std::vector<vec3> face(4);
      for (int k = 0; k < 4; ++k) {
        vec3 c;
        c[axis] = side ? hi[axis] : lo[axis];
        c[a] = (k == 1 || k == 2) ? hi[a] : lo[a];
        c[b] = k >= 2 ? hi[b] : lo[b];
        face[k] = c;
      }
      add_clipped(std::move(face), sides, region.points);
    }
  }
  if (!camera.orthographic && box.contains(camera.eye)) region.points.push_back(camera.eye);
  vec3 sum(0.0f);
  for (const vec3& p : region.points) sum += p;
  region.centroid = region.points.empty() ? box.center() : sum / float(region.points.size());

  // Planes: a square around the eye's foot, far larger than the box, clipped
  // to the frustum (beyond the box's footprint it makes no difference).
  const float reach = 1000.0f * glm::max(glm::length(box.extent()), glm::length(box.center() - camera.eye));
  for (int i = 0; i < plane_count; ++i) {
    const Plane& pl = planes[i];
    const vec3 foot = camera.eye - glm::dot(camera.eye - pl.point, pl.normal) * pl.normal;
    const vec3 helper = glm::abs(pl.normal.x) < 0.9f ? vec3(1.0f, 0.0f, 0.0f) : vec3(0.0f, 1.0f, 0.0f);
    const vec3 u = glm::normalize(glm::cross(helper, pl.normal)), v = glm::cross(pl.normal, u);
    add_clipped({foot + reach * (-u - v), foot + reach * (u - v), foot + reach * (u + v), foot + reach * (-u + v)},
                sides, region.plane_points);
  }

  const float span = 2.0f * camera.half_height / float(glm::max(height, 1));
  region.pixel = camera.orthographic ? span : span * glm::max(glm::dot(region.centroid - camera.eye, camera.forward), 1e-6f);
  return region;
}

}  // namespace penumbra

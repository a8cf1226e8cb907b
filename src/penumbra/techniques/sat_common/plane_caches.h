#pragma once
// Shadow caches on the scene's opaque planes (issue 14: a floor under the
// volume made cone-shadows' frame 3.3x phong's, because every floor pixel
// marched a cone; the volume's own samples read the 3D shadow cache). For
// each light and plane a 2D grid of the light's visibility over the plane's
// region the volume can shadow: the bounding rectangle, in the plane, of the
// volume box's corners projected onto it along the light (parallel for
// directional lights, from the light's position for point, sphere and disk
// lights). A technique whose march starts only where the light's axis ray
// crosses the volume box (cone-shadows: the cone ends where its axis leaves
// the box) sees nothing there outside that rectangle, so a read outside it is
// 1; inside, it is bilinear between the grid's nodes. A technique whose
// visibility reaches beyond the box's projection passes a grown box
// (filtered-sat: its patch's reach, filtered_shadow_box). A point light for
// which some corner does not lie between the light and the plane (the
// shadow reaches to infinity), or a light so oblique that the rectangle
// needs more than kMaxSide nodes a side, gets no grid, and its plane points
// are lit directly.
#include "penumbra/base/math.h"
#include "penumbra/scene/light.h"
#include "penumbra/scene/plane.h"

#include <cstdint>
#include <vector>

namespace penumbra {

// One light's grid on one plane; dims.x == 0: no grid (light directly).
struct PlaneCacheView {
  vec3 origin{0.0f};  // world position of node (0, 0)
  vec3 u{0.0f};       // grid x per world unit along the plane (the axis over the cell size)
  vec3 v{0.0f};       // grid y per world unit
  ivec2 dims{0};
  std::int64_t offset = 0;  // first texel in PlaneCaches' texels
};

// What kernels read: views[light * plane_count + plane] into one texel array.
struct PlaneCachesView {
  const PlaneCacheView* views = nullptr;
  const float* texels = nullptr;
  int plane_count = 0;
  int light_count = 0;

  PENUMBRA_HD bool has(int light, int plane) const {
    return views != nullptr && light < light_count && plane < plane_count &&
           views[light * plane_count + plane].dims.x > 0;
  }
  // Bilinear visibility at p on the plane (has(light, plane) must hold): 1
  // outside the grid's rectangle.
  PENUMBRA_HD float sample(int light, int plane, vec3 p) const {
    const PlaneCacheView& c = views[light * plane_count + plane];
    const vec3 d = p - c.origin;
    const float x = glm::dot(d, c.u), y = glm::dot(d, c.v);
    if (!(x >= 0.0f && y >= 0.0f && x <= float(c.dims.x - 1) && y <= float(c.dims.y - 1))) return 1.0f;
    const int x0 = glm::min(int(x), c.dims.x - 2), y0 = glm::min(int(y), c.dims.y - 2);
    const float fx = x - float(x0), fy = y - float(y0);
    const float* t = texels + c.offset + std::int64_t(y0) * c.dims.x + x0;
    const float bottom = t[0] + (t[1] - t[0]) * fx;
    const float top = t[c.dims.x] + (t[c.dims.x + 1] - t[c.dims.x]) * fx;
    return bottom + (top - bottom) * fy;
  }

  template <class Mirror> PlaneCachesView on_device(Mirror& m) const {
    PlaneCachesView d = *this;
    if (views == nullptr) return d;
    std::int64_t count = 0;
    for (int i = 0; i < light_count * plane_count; ++i) {
      const PlaneCacheView& c = views[i];
      count = glm::max(count, c.offset + std::int64_t(c.dims.x) * c.dims.y);
    }
    d.views = m.structure(views, std::size_t(light_count * plane_count), "the plane shadow caches");
    d.texels = count > 0 ? m.structure(texels, std::size_t(count), "the plane shadow caches") : nullptr;
    return d;
  }
};

// The grids of every light on every plane, and what they were built for.
class PlaneCaches {
 public:
  // Rebuilds the grids when the planes' geometry, the lights' placements or
  // `version` (what visibility reads: the technique's tables and cones)
  // changed; returns whether it did. cell: the grid spacing in world units;
  // visibility(light, p): the technique's direct visibility of light at p
  // (or the batch visibility(light, count, point, out), sat_common/batch.h).
  // A rectangle of more than kMaxSide nodes a side (a light grazing the
  // plane) gets no grid: its build would cost more than the frames it saves.
  static constexpr int kMaxSide = 1024;
  template <class Visibility>
  bool update(const std::vector<Light>& lights, const std::vector<Plane>& planes, const Box3& box, float cell,
              std::uint64_t version, const Visibility& visibility);
  // Whether update with these arguments would keep the grids as they are.
  bool current(const std::vector<Light>& lights, const std::vector<Plane>& planes, float cell,
               std::uint64_t version) const {
    return version == version_ && key(lights, planes, cell) == key_;
  }
  // Whether update would give `light` a grid on `plane`.
  static bool covers(const Light& light, const Plane& plane, const Box3& box, float cell) {
    return layout(light, plane, box, cell).dims.x > 0;
  }
  void clear();

  PlaneCachesView view() const;
  std::uint64_t bytes() const { return texels_.size() * sizeof(float) + views_.size() * sizeof(PlaneCacheView); }

 private:
  // The rectangle of one light on one plane (dims.x == 0: none), texels not filled.
  static PlaneCacheView layout(const Light& light, const Plane& plane, const Box3& box, float cell);
  // What the grids are built for: the planes' points and normals, the lights' placements, the cell.
  static std::vector<vec4> key(const std::vector<Light>& lights, const std::vector<Plane>& planes, float cell);

  std::vector<PlaneCacheView> views_;
  std::vector<float> texels_;
  std::vector<vec4> key_;  // the planes' points and normals and the lights' placements built for
  std::uint64_t version_ = ~std::uint64_t(0);
  int plane_count_ = 0;
  int light_count_ = 0;
};

}  // namespace penumbra

#include "penumbra/base/parallel.h"
#include "penumbra/techniques/sat_common/batch.h"

namespace penumbra {

template <class Visibility>
bool PlaneCaches::update(const std::vector<Light>& lights, const std::vector<Plane>& planes, const Box3& box,
                         float cell, std::uint64_t version, const Visibility& visibility) {
  if (current(lights, planes, cell, version)) return false;
  key_ = key(lights, planes, cell);
  version_ = version;
  plane_count_ = int(planes.size());
  light_count_ = int(lights.size());
  views_.assign(std::size_t(plane_count_) * std::size_t(light_count_), PlaneCacheView{});
  std::int64_t total = 0;
  for (int i = 0; i < light_count_; ++i) {
    for (int k = 0; k < plane_count_; ++k) {
      PlaneCacheView c = layout(lights[std::size_t(i)], planes[std::size_t(k)], box, cell);
      c.offset = total;
      total += std::int64_t(c.dims.x) * c.dims.y;
      views_[std::size_t(i * plane_count_ + k)] = c;
    }
  }
  texels_.assign(std::size_t(total), 1.0f);
  for (int i = 0; i < light_count_; ++i) {
    for (int k = 0; k < plane_count_; ++k) {
      const PlaneCacheView& c = views_[std::size_t(i * plane_count_ + k)];
      if (c.dims.x == 0) continue;
      // Node (x, y) sits at origin + x U + y V, where U, V are the in-plane
      // axes of one cell (u and v are those over the cell size squared).
      const vec3 U = c.u / glm::dot(c.u, c.u), V = c.v / glm::dot(c.v, c.v);
      evaluate_light_batch(
          visibility, std::size_t(i), std::int64_t(c.dims.x) * c.dims.y,
          [&](std::int64_t t) { return c.origin + float(t % c.dims.x) * U + float(t / c.dims.x) * V; },
          texels_.data() + c.offset);
    }
  }
  return true;
}

}  // namespace penumbra

#include "penumbra/techniques/ipsvi/light_cache_projection.h"

#include "penumbra/base/error.h"

#include <array>
#include <cmath>
#include <vector>

namespace penumbra {
namespace {

std::array<vec3, 8> box_corners(const Box3& box) {
  std::array<vec3, 8> corners;
  for (int i = 0; i < 8; ++i) {
    corners[i] = vec3(i & 1 ? box.upper.x : box.lower.x, i & 2 ? box.upper.y : box.lower.y,
                      i & 4 ? box.upper.z : box.lower.z);
  }
  return corners;
}

// Two unit vectors completing `axis` to a right-handed frame; u along the
// part of `preferred` across the axis where there is enough of it.
void complete_frame(vec3 axis, vec3 preferred, vec3& u, vec3& v) {
  const vec3 across = preferred - glm::dot(preferred, axis) * axis;
  if (glm::length(across) > 0.2f * glm::length(preferred) && glm::length(preferred) > 0.0f) {
    u = glm::normalize(across);
  } else {
    const vec3 helper = glm::abs(axis.x) < 0.9f ? vec3(1.0f, 0.0f, 0.0f) : vec3(0.0f, 1.0f, 0.0f);
    u = glm::normalize(glm::cross(helper, axis));
  }
  v = glm::cross(axis, u);
}

// A little margin (1% of the box's footprint on each side) so that points on
// the region's faces stay inside the outer texels.
constexpr float kMargin = 0.01f;

// Texel sizes are rounded up to powers of 2^(1/4), and the rectangle's centre
// to whole texels, so that small camera moves leave the grid where it was.
float snap_up(float t) { return std::exp2(std::ceil(4.0f * std::log2(t)) / 4.0f); }

struct Rect {
  vec2 lo{kInfinity}, hi{-kInfinity};
  void add(vec2 p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  bool empty() const { return !(lo.x <= hi.x && lo.y <= hi.y); }
};

// A fitted octahedral map: its frame (side_u, side_v, axis) and the
// rectangle of the map (in [0, 1]^2) that holds the directions from `light`
// toward the visible part of the box. That part is convex, so its directions
// form a cone spanned by its corners, within a hemisphere when the light lies
// outside it. The map's axis lies about the centre of the smallest cone
// holding the corner directions, so that they lie about the map's centre,
// away from its folded outer edges. Within one octant the map is a
// central projection onto a face of the octahedron (folded affinely below
// z = 0), so the arc between two corners' directions maps to a straight
// segment there, and the cone's image is bounded by such segments between the
// points where they cross the planes x = 0, y = 0 and z = 0 of the frame.
// Every pair of corners is taken, which includes every edge. The whole map
// (and the world's frame) where the light lies in the visible part of the
// box (all directions are needed), the region is not known, or an arc crosses
// x = 0 or y = 0 below z = 0, the map's folded outer edges, across which the
// directions continue on the opposite side. Visible planes are left out:
// their points' light rays may run outside the map, and ipsvi marches those
// (plane_light in ipsvi_ray.h).
struct OctahedralFit {
  Rect rect{vec2(0.0f), vec2(1.0f)};
  vec3 u{1.0f, 0.0f, 0.0f}, v{0.0f, 1.0f, 0.0f}, axis{0.0f, 0.0f, 1.0f};
  bool whole() const { return rect.lo == vec2(0.0f) && rect.hi == vec2(1.0f); }
};

OctahedralFit fit_octahedral(vec3 light, const LightCacheRegion& region) {
  const OctahedralFit whole;
  if (region.points.empty() || region.bounds.empty()) return whole;
  bool inside = true;
  for (const vec4& h : region.bounds) inside = inside && glm::dot(vec3(h), light) + h.w >= 0.0f;
  if (inside) return whole;
  std::vector<vec3> directions;
  vec3 mean(0.0f);
  for (const vec3& c : region.points) {
    const float l = glm::length(c - light);
    if (!(l > 0.0f)) return whole;
    directions.push_back((c - light) / l);
    mean += directions.back();
  }
  if (!(glm::length(mean) > 1e-3f)) return whole;
  // The axis: about the centre of the smallest cone around the directions,
  // stepping from their mean toward the farthest one by shrinking steps
  // (Badoiu and Clarkson's iteration for the smallest enclosing ball).
  OctahedralFit fit;
  fit.axis = glm::normalize(mean);
  for (int k = 1; k <= 200; ++k) {
    const vec3* farthest = &directions[0];
    for (const vec3& d : directions) {
      if (glm::dot(fit.axis, d) < glm::dot(fit.axis, *farthest)) farthest = &d;
    }
    fit.axis = glm::normalize(fit.axis + (*farthest - fit.axis) / float(k + 1));
  }
  complete_frame(fit.axis, vec3(0.0f), fit.u, fit.v);
  auto local = [&](vec3 c) {
    const vec3 q = c - light;
    return vec3(glm::dot(q, fit.u), glm::dot(q, fit.v), glm::dot(q, fit.axis));
  };
  Rect r;
  bool folded = false;
  const std::size_t n = region.points.size();
  for (std::size_t i = 0; i < n && !folded; ++i) {
    const vec3 a = local(region.points[i]);
    r.add(LightCacheProjection::octahedral_encode(a));
    for (std::size_t j = i + 1; j < n; ++j) {
      const vec3 b = local(region.points[j]);
      for (int axis = 0; axis < 3; ++axis) {
        if ((a[axis] < 0.0f) == (b[axis] < 0.0f)) continue;
        vec3 c = a + (b - a) * (a[axis] / (a[axis] - b[axis]));
        c[axis] = 0.0f;
        if (axis < 2 && c.z < 0.0f) folded = true;
        r.add(LightCacheProjection::octahedral_encode(c));
      }
    }
  }
  if (folded || r.empty()) return whole;
  fit.rect.lo = glm::max(r.lo - vec2(kMargin), vec2(0.0f));
  fit.rect.hi = glm::min(r.hi + vec2(kMargin), vec2(1.0f));
  return fit;
}

}  // namespace

LightCacheProjection make_light_cache_projection(const Light& light, const Box3& box, int size) {
  if (size < 1) throw InvalidArgument("cache_size", "must be at least 1");
  LightCacheRegion whole;
  whole.max_aspect = 1.0f;
  return fit_light_cache_projection(light, box, whole, size, size);
}

LightCacheProjection fit_light_cache_projection(const Light& light, const Box3& box, const LightCacheRegion& region,
                                                int size, int max_size, bool trim) {
  if (size < 0) throw InvalidArgument("cache_size", "must be at least 1");
  LightCacheProjection p;
  const auto corners = box_corners(box);
  const float diagonal = glm::max(glm::length(box.extent()), 1e-6f);
  const int cap = glm::max(max_size, 16);

  // The mapping and its axis depend on the light and the box only.
  float lowest = kInfinity;  // orthographic: depth origin along the axis
  if (light.at_infinity()) {
    p.mapping = LightMapping::Orthographic;
    p.axis = glm::normalize(light.direction);
    for (const vec3& c : corners) {
      lowest = glm::min(lowest, glm::dot(c, p.axis));
      p.max_depth = glm::max(p.max_depth, glm::dot(c, p.axis));
    }
    p.max_depth -= lowest;
  } else {
    p.origin = light.position;
    for (const vec3& c : corners) p.max_depth = glm::max(p.max_depth, glm::length(c - light.position));
    p.axis = glm::normalize(box.center() - light.position);
    // A frustum works while every corner lies well in front of the light;
    // otherwise (light inside or right beside the box) map all directions.
    bool frustum = !box.contains(light.position) && is_finite(p.axis.x);
    for (const vec3& c : corners) {
      const vec3 q = c - light.position;
      if (frustum && glm::dot(q, p.axis) < 0.3f * glm::length(q)) frustum = false;  // beyond ~72 degrees off axis
    }
    p.mapping = frustum ? LightMapping::Perspective : LightMapping::Octahedral;
  }

  if (p.mapping == LightMapping::Octahedral) {
    p.axis = vec3(0.0f, 0.0f, 1.0f);
    p.side_u = vec3(1.0f, 0.0f, 0.0f);
    p.side_v = vec3(0.0f, 1.0f, 0.0f);
    const OctahedralFit fit = trim ? fit_octahedral(light.position, region) : OctahedralFit{};
    const Rect& need = fit.rect;
    const vec2 extent = need.hi - need.lo;
    const float longest = glm::max(extent.x, extent.y);
    // Automatic: texels a pixel wide where the light sees the volume, at up to
    // its half-diagonal however close it is to the centre (measuring at the
    // centre distance, 0 for a light at the centre, gave a 16^2 cache and
    // radial light leaks); this many across the whole map.
    const float reach = glm::max(0.5f * diagonal, glm::length(box.center() - light.position));
    const float pixel_rule = glm::min(reach * 3.5449077f / glm::max(region.pixel, 1e-6f), 1e7f);
    if (fit.whole()) {  // the whole map, n x n, in the world's frame
      p.size = size;
      if (size == 0) {
        p.size = glm::clamp(int(std::ceil(pixel_rule)), 16, cap);
        if (region.max_map_texels > 0.0 && double(p.size) * double(p.size) > region.max_map_texels) {
          p.size = glm::max(16, int(std::floor(std::sqrt(region.max_map_texels))));
        }
      }
      p.rows = p.size;
      p.scale = vec2(float(p.size));
      return p;
    }
    // A part of the map: texels of the same width as over the whole map,
    // at most `cap` along the longer side and (automatic) within the texel
    // budget, their size snapped and the rectangle aligned to whole texels.
    p.axis = fit.axis;
    p.side_u = fit.u;
    p.side_v = fit.v;
    float across = float(size) / longest;  // texels across the whole map
    if (size == 0) {
      across = glm::clamp(glm::ceil(pixel_rule), 16.0f / longest, float(cap) / longest);
      const double texels = double(across) * double(across) * double(extent.x) * double(extent.y);
      const double budget = region.max_map_texels;
      if (budget > 0.0 && texels > budget) {
        across = glm::max(16.0f / longest, across * float(std::sqrt(budget / texels)));
      }
      across = 1.0f / snap_up(1.0f / across);
    }
    p.scale = vec2(across);
    p.lower = glm::floor(need.lo * across) / across;
    p.size = glm::max(1, int(std::ceil((need.hi.x - p.lower.x) * across)));
    p.rows = glm::max(1, int(std::ceil((need.hi.y - p.lower.y) * across)));
    return p;
  }

  complete_frame(p.axis, region.long_direction, p.side_u, p.side_v);
  const bool ortho = p.mapping == LightMapping::Orthographic;
  // Plane coordinates: world units across the light, or tan units.
  auto plane_coords = [&](vec3 c, bool& valid) {
    if (ortho) return vec2(glm::dot(c, p.side_u), glm::dot(c, p.side_v));
    const vec3 q = c - light.position;
    const float z = glm::dot(q, p.axis);
    valid = z > 0.3f * glm::length(q);
    return vec2(glm::dot(q, p.side_u), glm::dot(q, p.side_v)) / glm::max(z, 1e-12f);
  };
  Rect whole, fitted, planes;
  for (const vec3& c : corners) {
    bool in_front = true;  // every corner is, for a perspective mapping
    whole.add(plane_coords(c, in_front));
  }
  for (const vec3& c : region.points) {
    bool ok = true;
    const vec2 a = plane_coords(c, ok);
    if (ok) fitted.add(a);
  }
  // Light rays through visible plane points matter where they cross the box.
  // (From a point light a polygon partly behind the light has no bounding
  // rectangle of its corners: such scenes keep the whole box.)
  bool planes_ok = ortho;
  for (const vec3& c : region.plane_points) {
    if (!planes_ok) break;
    planes.add(plane_coords(c, planes_ok));
  }
  if (!region.plane_points.empty()) {
    if (!planes_ok) {
      fitted = whole;
    } else if (!planes.empty()) {
      fitted.add(glm::max(planes.lo, whole.lo));
      fitted.add(glm::min(planes.hi, whole.hi));
    }
  }
  if (region.points.empty() && region.plane_points.empty()) fitted = whole;
  // Keep the fit inside the box's footprint (and the box's if nothing is seen).
  Rect r;
  r.lo = glm::max(fitted.lo, whole.lo);
  r.hi = glm::min(fitted.hi, whole.hi);
  if (r.empty()) r = whole;
  const vec2 whole_extent = whole.hi - whole.lo;
  const float whole_max = glm::max(glm::max(whole_extent.x, whole_extent.y), 1e-6f);
  r.lo -= vec2(kMargin * whole_max);
  r.hi += vec2(kMargin * whole_max);
  const vec2 extent = glm::max(r.hi - r.lo, vec2(1e-3f * whole_max));

  // Texels about a pixel wide across the short side, at most max_aspect
  // times longer along the long one.
  const float aspect = glm::max(region.max_aspect, 1.0f);
  int n = size;
  if (n == 0) {
    const vec3 middle = region.points.empty() ? box.center() : region.centroid;
    const float distance = ortho ? 1.0f : glm::max(glm::length(middle - light.position), 1e-6f);
    const float pixel = glm::max(region.pixel, 1e-6f) / distance;
    const vec2 texels = extent / pixel;
    const float wanted = glm::max(glm::min(texels.x, texels.y), glm::max(texels.x, texels.y) / aspect);
    n = glm::clamp(int(std::ceil(glm::min(wanted, 1e7f))), 16, cap);
  }
  // Texels no more than `aspect` times longer than wide: across a long
  // rectangle they are wider than its extent over n needs, and with `trim`
  // fewer of them cover it (one more than the extent's texels, for the
  // centre's rounding to whole texels below).
  vec2 t;
  glm::ivec2 counts;
  auto grid = [&](int texels) {
    t = extent / float(glm::max(texels - 1, 1));
    counts = glm::ivec2(texels);
    const int fewest = glm::min(texels, 16);
    if (t.x > aspect * t.y) {
      t.y = t.x / aspect;
      if (trim) counts.y = glm::clamp(int(std::ceil(extent.y / t.y)) + 1, fewest, texels);
    }
    if (t.y > aspect * t.x) {
      t.x = t.y / aspect;
      if (trim) counts.x = glm::clamp(int(std::ceil(extent.x / t.x)) + 1, fewest, texels);
    }
  };
  grid(n);
  // An automatic grid over the region's texel budget gets coarser texels,
  // both sides alike (the count of each side scales with n).
  const double budget = region.max_texels;
  for (int pass = 0; size == 0 && budget > 0.0 && pass < 4 && n > 16; ++pass) {
    const double texels = double(counts.x) * double(counts.y);
    if (texels <= budget) break;
    n = glm::max(16, int(std::floor(double(n) * std::sqrt(budget / texels))));
    grid(n);
  }
  p.size = counts.x;
  p.rows = counts.y;
  t = vec2(snap_up(t.x), snap_up(t.y));
  const vec2 centre = glm::round(0.5f * (r.lo + r.hi) / t) * t;
  const vec2 lower = centre - 0.5f * vec2(counts) * t;
  p.scale = vec2(1.0f) / t;
  if (ortho) {
    p.origin = lower.x * p.side_u + lower.y * p.side_v + lowest * p.axis;
  } else {
    p.lower = lower;
  }
  return p;
}

}  // namespace penumbra

#pragma once
// The light-space projection shared by the shadow-map techniques (shadow-map,
// deep-shadow-map, cssm): which ray from the light each map texel stands for,
// and where a world point falls in the map.
//
//   directional (and distant) lights: orthographic along the light's
//     direction, a square window fitted to the volume box's projection;
//   point (sphere, disk) lights: perspective from the light position, a
//     square window on the plane at unit distance fitted to the box's corners;
//     when the box is too wide to fit one frustum (light inside or close to
//     it) a cube map of six 90-degree faces around the light, each of half
//     the resolution (a face's texels then subtend about what the widest
//     single frustum's do, and the cube holds 1.5x the texels of one map).
//
// Texel (x, y) of a face has its centre at (x + 0.5, y + 0.5) in texel
// coordinates. Depth is the distance along the texel's ray: from a plane in
// front of the box (orthographic) or from the light (perspective), in world
// units. The window covers the whole box (with a margin of a few texels), so
// a point outside the window of a single-face map sees no volume toward the
// light: such lookups count as lit.
#include "penumbra/base/lanes.h"
#include "penumbra/base/math.h"
#include "penumbra/base/ray.h"
#include "penumbra/scene/light.h"

#include <cstdint>

namespace penumbra {

enum class LightProjectionKind : std::uint8_t { None, Orthographic, Perspective };

struct LightFace {
  vec3 u{1.0f, 0.0f, 0.0f};  // texel x grows along u
  vec3 v{0.0f, 1.0f, 0.0f};  // texel y grows along v
  vec3 w{0.0f, 0.0f, 1.0f};  // away from the light: the depth axis
};

// A world point as the map sees it: face, continuous texel coordinates and
// depth along the light ray.
struct LightMapPoint {
  int face = 0;
  vec2 texel{0.0f};
  float depth = 0.0f;
};

template <class L> struct LightMapPointL {
  typename L::Int face;
  typename L::Float x, y;  // continuous texel coordinates
  typename L::Float depth;
};

struct LightProjection {
  LightProjectionKind kind = LightProjectionKind::None;  // None: no map (environment lights)
  int resolution = 0;  // texels per side of each face (half the requested resolution for a cube map)
  int face_count = 0;  // 1, or 6 for a cube map
  vec3 origin{0.0f};   // orthographic: a point in front of the box on its axis; perspective: the light
  vec2 window_center{0.0f};  // window centre in (u, v) world units (ortho) or tangents (perspective)
  float window_half = 1.0f;  // half the window side, same units
  LightFace faces[6];

  PENUMBRA_HD std::int64_t texels_per_face() const { return std::int64_t(resolution) * resolution; }
  PENUMBRA_HD std::int64_t texel_count() const { return texels_per_face() * face_count; }

  // Texel coordinates -> window coordinates (u, v) and back.
  PENUMBRA_HD vec2 window_from_texel(vec2 t) const {
    return window_center + (t / float(resolution) * 2.0f - 1.0f) * window_half;
  }
  PENUMBRA_HD vec2 texel_from_window(vec2 a) const {
    return ((a - window_center) / window_half + 1.0f) * 0.5f * float(resolution);
  }

  // World size of one texel at `depth` along its ray: constant for an
  // orthographic map, growing with the distance from the light for a
  // perspective one (the window's obliquity ignored: a scale for biases).
  template <class F> PENUMBRA_HD F texel_footprint(F depth) const {
    const float per_texel = 2.0f * window_half / float(resolution);
    if (kind == LightProjectionKind::Perspective) return depth * per_texel;
    return F(per_texel);
  }

  // The light ray through texel coordinates t of `face`; its parameter is the
  // depth the map stores.
  PENUMBRA_HD Ray texel_ray(int face, vec2 t) const {
    const LightFace& f = faces[face];
    const vec2 a = window_from_texel(t);
    if (kind == LightProjectionKind::Orthographic) return Ray{origin + a.x * f.u + a.y * f.v, f.w};
    return Ray{origin, glm::normalize(f.w + a.x * f.u + a.y * f.v)};
  }

  // Where p falls in the map. False when the map cannot see p (no map, or p
  // behind a perspective light): such points are lit.
  PENUMBRA_HD bool locate(vec3 p, LightMapPoint& out) const {
    LightMapPointL<ScalarLanes> q;
    if (!locate<ScalarLanes>(p, q)) return false;
    out.face = q.face;
    out.texel = vec2(q.x, q.y);
    out.depth = q.depth;
    return true;
  }

  // The same for one point or a packet of them (base/lanes.h): the lanes
  // that the map sees. A cube map's lanes may fall on different faces.
  template <class L>
  PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Mask locate(const typename L::Vec3& p, LightMapPointL<L>& out) const {
    using F = typename L::Float;
    using I = typename L::Int;
    using V = typename L::Vec3;
    using M = typename L::Mask;
    const V d = p - V(origin);
    const float scale = 0.5f * float(resolution);
    if (kind == LightProjectionKind::Orthographic) {
      const LightFace& f = faces[0];
      out.face = I(0);
      out.x = ((dot(d, V(f.u)) - window_center.x) / window_half + 1.0f) * scale;
      out.y = ((dot(d, V(f.v)) - window_center.y) / window_half + 1.0f) * scale;
      out.depth = dot(d, V(f.w));
      return M(true);
    }
    if (kind != LightProjectionKind::Perspective) return M(false);
    V u(faces[0].u), v(faces[0].v), w(faces[0].w);
    out.face = I(0);
    if (face_count == 6) {
      // The face of the dominant axis, its frame gathered per lane.
      const F ax = max(d.x, -d.x), ay = max(d.y, -d.y), az = max(d.z, -d.z);
      const I axis = select(ax >= ay, select(ax >= az, I(0), I(2)), select(ay >= az, I(1), I(2)));
      const F along = select(axis == I(0), d.x, select(axis == I(1), d.y, d.z));
      out.face = axis * 2 + select(along < 0.0f, I(1), I(0));
      const float* frames = &faces[0].u.x;  // 9 floats per face
      const typename L::Index base = typename L::Index(out.face) * 9;
      u = V(gather(frames, base), gather(frames, base + 1), gather(frames, base + 2));
      v = V(gather(frames, base + 3), gather(frames, base + 4), gather(frames, base + 5));
      w = V(gather(frames, base + 6), gather(frames, base + 7), gather(frames, base + 8));
    }
    const F dw = dot(d, w);
    const M seen = dw > 0.0f;
    if (none(seen)) return seen;
    out.x = ((dot(d, u) / dw - window_center.x) / window_half + 1.0f) * scale;
    out.y = ((dot(d, v) / dw - window_center.y) / window_half + 1.0f) * scale;
    out.depth = length(d);
    return seen;
  }
};

// Largest window half-size (tangent of the half field of view) of a single
// perspective face; a wider box gets a cube map.
inline constexpr float kMaxPerspectiveHalfTangent = 1.5f;

// The projection of `light` fitted to `box` at `resolution` texels per side
// (resolution / 2 per cube face).
// Environment lights get kind None (they cast no map: the single-scattering
// techniques give them no direct light).
LightProjection make_light_projection(const Light& light, const Box3& box, int resolution);

}  // namespace penumbra

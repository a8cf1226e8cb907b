#pragma once
// A light-space map: a fixed number of floats per texel over every face of a
// LightProjection (1 for a shadow map, 3 for a CSSM, 4 per node for a deep
// shadow map). LightMap owns the texels; LightMapView is the plain struct the
// query kernels read.
#include "penumbra/base/parallel.h"
#include "penumbra/techniques/light_space/light_projection.h"

#include <cstdint>
#include <string>
#include <vector>

namespace penumbra {

struct LightMapView {
  LightProjection projection;
  const float* texels = nullptr;
  int values_per_texel = 0;

  // The values of texel (x, y) of `face`, or nullptr outside a single-face
  // map (no volume lies toward the light there: lit). Cube maps clamp to the
  // face's edge, so filters near a cube edge reuse the border texels.
  PENUMBRA_HD const float* texel(int face, int x, int y) const {
    const int n = projection.resolution;
    if (projection.face_count == 6) {
      x = x < 0 ? 0 : (x >= n ? n - 1 : x);
      y = y < 0 ? 0 : (y >= n ? n - 1 : y);
    } else if (x < 0 || y < 0 || x >= n || y >= n) {
      return nullptr;
    }
    return texels + (projection.texels_per_face() * face + std::int64_t(y) * n + x) * values_per_texel;
  }

  // The same per lane (base/lanes.h): the offset of the texel's first value
  // in `texels`, and in `inside` whether the map has that texel (0 is
  // returned where it has not, a safe place to read).
  template <class L>
  PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Index texel_offset(typename L::Int face, typename L::Int x,
                                                                   typename L::Int y,
                                                                   typename L::Mask& inside) const {
    using I = typename L::Int;
    using X = typename L::Index;
    const int n = projection.resolution;
    if (projection.face_count == 6) {
      x = max(I(0), min(x, I(n - 1)));
      y = max(I(0), min(y, I(n - 1)));
      inside = typename L::Mask(true);
    } else {
      inside = (x >= I(0)) & (y >= I(0)) & (x < I(n)) & (y < I(n));
      x = select(inside, x, I(0));
      y = select(inside, y, I(0));
    }
    return (X(face) * X(projection.texels_per_face()) + X(y) * X(n) + X(x)) * X(values_per_texel);
  }

  // The change per texel of value `index` (a depth) around texel (x, y) of
  // `face`, per axis: of the forward and backward differences the smaller in
  // magnitude (one side of a depth discontinuity is continuous), sign kept;
  // +inf depths (empty rays) count as `far` and each axis is clamped to
  // +-cap. For slope-scaled biases and depth-aware filters.
  template <class L>
  PENUMBRA_HD PENUMBRA_FORCE_INLINE void depth_gradient(typename L::Int face, typename L::Int x, typename L::Int y,
                                                        int index, typename L::Float centre, typename L::Float cap,
                                                        typename L::Float& gx, typename L::Float& gy) const {
    using F = typename L::Float;
    using I = typename L::Int;
    const auto value = [&](I tx, I ty) {
      typename L::Mask inside;
      const auto at = texel_offset<L>(face, tx, ty, inside);
      return select(inside, finite_depth(gather(texels, at + typename L::Index(index))), F(kFarDepth));
    };
    const F c = finite_depth(centre);
    const auto pick = [&](F forward, F backward) {
      const F g = select(max(forward, -forward) <= max(backward, -backward), forward, backward);
      return max(-cap, min(g, cap));
    };
    gx = pick(value(x + I(1), y) - c, c - value(x - I(1), y));
    gy = pick(value(x, y + I(1)) - c, c - value(x, y - I(1)));
  }

  // The receiver plane of value `index` (a depth) at continuous texel
  // coordinates (qx, qy): the gradient (gx, gy) per texel of the texel
  // holding the point (depth_gradient, clamped to +-cap). A lookup of texel
  // (tx, ty) at depth z for that point reads depth
  //   z + gx (tx + 0.5 - qx) + gy (ty + 0.5 - qy):
  // the same depth below a planar occluder as the point's own ray.
  template <class L>
  PENUMBRA_HD PENUMBRA_FORCE_INLINE void plane_gradient(typename L::Int face, typename L::Float qx,
                                                        typename L::Float qy, int index, typename L::Float cap,
                                                        typename L::Float& gx, typename L::Float& gy) const {
    using F = typename L::Float;
    const typename L::Int x = to_int(floor(qx)), y = to_int(floor(qy));
    typename L::Mask inside;
    const auto at = texel_offset<L>(face, x, y, inside);
    const F centre = select(inside, gather(texels, at + typename L::Index(index)), F(kFarDepth));
    depth_gradient<L>(face, x, y, index, centre, cap, gx, gy);
  }

  // plane_gradient at point q, clamped to max_slope texel footprints per
  // texel at q's depth and times `scale` (the slope bias of a technique;
  // 0: no reads, a zero gradient).
  template <class L>
  PENUMBRA_HD PENUMBRA_FORCE_INLINE void receiver_plane(const LightMapPointL<L>& q, int index, float max_slope,
                                                        float scale, typename L::Float& gx,
                                                        typename L::Float& gy) const {
    gx = typename L::Float(0.0f);
    gy = typename L::Float(0.0f);
    if (scale <= 0.0f) return;
    plane_gradient<L>(q.face, q.x, q.y, index, max_slope * projection.texel_footprint(q.depth), gx, gy);
    gx *= scale;
    gy *= scale;
  }

  // Depths as stored are +inf where a ray meets nothing; finite_depth maps
  // them to kFarDepth so that differences stay finite.
  static constexpr float kFarDepth = 1e30f;
  template <class F> PENUMBRA_HD static F finite_depth(F depth) { return min(depth, F(kFarDepth)); }

  // Whether packet offsets (32-bit) reach every value of the map.
  PENUMBRA_HD bool fits_packets() const {
    return projection.texel_count() * values_per_texel < (std::int64_t(1) << 31);
  }
};

// The device copy of one view per light (backends/device.h's on_device): the
// texels mirrored, the views copied for the frame.
template <class Mirror> const LightMapView* light_maps_on_device(const LightMapView* maps, Mirror& m) {
  std::vector<LightMapView> copy(maps, maps + m.light_count());
  for (LightMapView& map : copy) {
    map.texels = m.structure(map.texels, std::size_t(map.projection.texel_count()) * std::size_t(map.values_per_texel),
                             "the light maps");
  }
  return m.frame(copy, "the light map views");
}

class LightMap {
 public:
  LightMap() = default;
  // Moves are declared noexcept so that a std::vector<LightMap> moves its
  // maps when it grows: the implicit move is not (GLM_FORCE_CTOR_INIT gives
  // glm's vectors copy constructors that are not noexcept), and the vector
  // then copied every map's texels.
  LightMap(LightMap&&) noexcept = default;
  LightMap& operator=(LightMap&&) noexcept = default;
  LightMap(const LightMap&) = default;
  LightMap& operator=(const LightMap&) = default;
  // Checks projection.texel_count() * values_per_texel floats against the
  // memory budget (OutOfMemoryBudget naming `what`) and allocates them.
  LightMap(const std::string& what, const LightProjection& projection, int values_per_texel);

  const LightProjection& projection() const { return projection_; }
  int values_per_texel() const { return values_per_texel_; }
  float* texel(std::int64_t index) { return texels_.data() + index * values_per_texel_; }
  const float* texel(std::int64_t index) const { return texels_.data() + index * values_per_texel_; }
  std::uint64_t bytes() const { return texels_.size() * sizeof(float); }
  LightMapView view() const { return LightMapView{projection_, texels_.data(), values_per_texel_}; }

  // Fills every texel in parallel: fill(ray, texel_index, values) writes the
  // texel's values_per_texel floats, given the light ray through its centre.
  template <class Fill> void fill(const Fill& fill_texel) {
    const LightProjection& p = projection_;
    const int n = p.resolution;
    parallel_for(
        0, std::int64_t(p.face_count) * n,
        [&](std::int64_t first_row, std::int64_t last_row) {
          for (std::int64_t row = first_row; row < last_row; ++row) {
            const int face = int(row / n);
            const int y = int(row % n);
            for (int x = 0; x < n; ++x) {
              const std::int64_t index = row * n + x;
              fill_texel(p.texel_ray(face, vec2(float(x) + 0.5f, float(y) + 0.5f)), index, texel(index));
            }
          }
        },
        4);
  }

 private:
  LightProjection projection_;
  int values_per_texel_ = 0;
  std::vector<float> texels_;
};

}  // namespace penumbra

#pragma once
// Zero-variance (single-tap) lights carried along their rays across empty
// space (issue 23): hard shadows without the slab-to-slab re-sampling blur.
//
// A single-tap kernel moves light by the same affine map every slab
// (light_propagation.h: p' = c + s (p - c) + w from slab k to slab k - 1, s
// and w the same for every texel), so a grid of texels that starts on the
// pixel grid and follows the light rays stays a regular grid in pixel space:
// texel centre g (texel coordinates) sits at
//   A_k(g) = c + scale_k (g - g_c) + offset_k,
// with scale_k = scale_{k-1} / s and offset_k = (offset_{k-1} - w) / s.
// Moving such a grid to the next slab changes (scale, offset), not the texels.
//
// The light itself stays where the slab loop keeps it, on the pixel grid:
// every slab it is re-sampled from the previous one (convolve_slab) and
// attenuated by each pixel's own column, so a pixel's light has crossed the
// medium it shows (a dense surface is lit by light that reached it, not by
// light a neighbouring column darkened). Beside it, the carried grid holds
// the same light without re-sampling:
//   - a texel whose crossing of a slab touched the medium (any of the four
//     pixels around it has optical depth there) is attenuated by that slab's
//     transmittance where it crossed it (the four pixels' transmittances,
//     bilinear); elsewhere it keeps its value as it moves. Its light is never
//     re-sampled, inside a medium either: taking the pixel grid's light there
//     (one bilinear read of light re-sampled every slab) widened a hard
//     shadow by the occluder's depth in slabs;
//   - a pixel takes its light from the carried grid (one bilinear read)
//     instead of the re-sampled value when its light crossed no medium in the
//     last slab (the four pixels around where it came from have none) and
//     the four texels it reads have not touched a medium for `min_age`
//     slabs (about a pixel of the light's sideways travel).
// So a receiver's light, once it has crossed empty space, is read once, on
// arriving, and its occluders' edges are each one bilinear read of a slab's
// transmittance. Re-sampling every slab left hard shadows 2.4-3.5 px wide
// where shadow-rays draws 0.9-1.5 px (the blur grows with the slab count).
// The age condition keeps the pixel grid's light next to a medium: a texel
// that took its light between a dense column and a clear one holds a mix of
// both, and read by the clear pixel beside a dense surface it would darken
// it (a dense box's lit faces: 0.374 against the path tracer's 0.422, 0.411
// re-sampled), where the re-sampled light has come down the pixel's own
// column.
//
// Where the volume is the only medium (no meshes), a texel that touches it
// samples the volume on its own ray at the slab's middle instead
// (advance_sampled): one trilinear sample and TF lookup, not the bilinear
// read of the four pixel columns' transmittances. Those weights cycle as
// the texels drift past the columns, and under a thin translucent sheet the
// cycle printed a moire into its shadow (the head CT's floor: structured
// error halved; docs/convolution.md, "Texels that sample the volume"). A
// sharp step in the medium is then placed to within half a texel rather
// than blurred over one.
//
// Two re-bases keep the grid over the frame: an integer shift of the texels
// (an exact copy) whenever |offset| passes a few texels, so the grid follows
// light that drifts sideways; and a re-sampling onto the pixel grid when a
// perspective camera has shrunk it (scale = z_0 / z_k) below the scale it was
// sized for (at most one per halving of scale; never with an orthographic
// camera). Texels beyond the grid's edge are its edge texels (clamp-to-edge),
// as for the pixel grid's buffers.
#include "penumbra/backends/cpu/packets.h"
#include "penumbra/base/lanes.h"
#include "penumbra/base/math.h"
#include "penumbra/base/parallel.h"
#include "penumbra/techniques/convolution/light_propagation.h"

#include <cmath>
#include <cstdint>
#include <vector>

namespace penumbra {

struct CarriedGrid {
  static constexpr int kShiftTexels = 4;  // the offset a grid runs up before an integer shift
  int width = 0, height = 0;  // texels
  vec2 center{0.0f};          // the frame's centre c, pixel coordinates
  vec2 grid_center{0.0f};     // g_c, texel coordinates
  float scale = 1.0f;         // frame pixels per texel
  vec2 offset{0.0f};

  // Frame pixel coordinates of texel (x, y)'s centre.
  PENUMBRA_HD vec2 position(int x, int y) const {
    return center + scale * (vec2(float(x) + 0.5f, float(y) + 0.5f) - grid_center) + offset;
  }
  // Continuous texel coordinates (centres at +0.5) of frame pixel coordinates.
  PENUMBRA_HD vec2 texel_of(vec2 p) const { return grid_center + (p - center - offset) / scale; }
};

// A grid over a frame of frame_width x frame_height pixels that keeps
// covering it (with 2 texels of read support) down to scale `min_scale`.
CarriedGrid carried_grid(int frame_width, int frame_height, float min_scale);

// Follow the light from the slab the grid is on to the next, whose texels map
// to it by `mapping` with the tap's pixel offset w (convolve_texel_mapped).
void advance_carried_grid(CarriedGrid& grid, const SlabMapping& mapping, vec2 w);

// Re-bases (each copies `planes` planes of width x height texels from `from`
// to `to`). Once the offset passes kShiftTexels texels on an axis, the
// integer shift n that brings it within half a texel, applied (texel x of the
// new grid is texel x + n of the old); ivec2(0) when none is needed, and then
// `to` is not written.
ivec2 shift_carried_grid(CarriedGrid& grid, const float* from, float* to, int planes);
// Onto the pixel grid (scale 1, no offset), re-sampled with the clamped
// Catmull-Rom read of single-tap slab steps.
void resample_carried_grid(CarriedGrid& grid, const float* from, float* to, int planes);

// MediumMask's lookup over a lane type.
struct MediumMaskView {
  const std::uint8_t* mask = nullptr;  // (width + 1) x (height + 1)
  int width = 0, height = 0;

  template <class L>
  PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Mask touches(typename L::Float px, typename L::Float py) const {
    using F = typename L::Float;
    using I = typename L::Int;
    const I x0 = to_int(floor(clamp(px - 0.5f, F(-1.0f), F(float(width - 1)))));
    const I y0 = to_int(floor(clamp(py - 0.5f, F(-1.0f), F(float(height - 1)))));
    const I i = (x0 + I(1)) + I(width + 1) * (y0 + I(1));
    const std::int64_t count = std::int64_t(width + 1) * std::int64_t(height + 1);
    return load_voxel(mask, typename L::Index(i), count) > F(0.0f);
  }
};

// Which frame positions have a medium among the four pixels a bilinear read
// there takes (clamp-to-edge), for one slab: the slab loop flags the pixels
// where the slab has optical depth, build() dilates the flags once per slab,
// and a query is one lookup. Beside the flags, the slab's extinction per
// pixel (`channels` planes: the optical depth along the pixel's column per
// unit length of a light's path through the slab), which the slab loop writes
// where it flags a pixel and leaves at 0 elsewhere.
class MediumMask {
 public:
  void resize(int frame_width, int frame_height, int channels = 1);  // all clear
  std::uint8_t* flags() { return any_.data(); }     // per pixel: 1 where the slab has a medium
  float* extinction(int c = 0) { return extinction_.data() + std::size_t(c) * any_.size(); }
  const float* extinction(int c = 0) const { return extinction_.data() + std::size_t(c) * any_.size(); }
  void build();
  // Whether the last build() found any flag set (else touches() is false everywhere).
  bool any() const { return any_set_; }
  // p in frame pixel coordinates, pixel centres at +0.5.
  bool touches(vec2 p) const { return view().touches<ScalarLanes>(p.x, p.y); }
  MediumMaskView view() const { return MediumMaskView{mask_.data(), width_, height_}; }

 private:
  int width_ = 0, height_ = 0;
  std::vector<std::uint8_t> any_;   // the flags
  std::vector<std::uint8_t> mask_;  // (width + 1) x (height + 1): entry (x0 + 1, y0 + 1) for pixels x0..x0+1, y0..y0+1
  std::vector<float> extinction_;
  bool any_set_ = false;
};

// What propagate reads for one light, as a plain view for the lane-generic
// read below (one source for one pixel and for 8 or 16).
struct CarriedReadView {
  static constexpr int kMaxChannels = 3;
  MediumMaskView medium;  // the last slab's medium
  CarriedGrid grid;
  const float* texels = nullptr;   // `channels` planes of grid texels
  const float* touched = nullptr;  // the plane of the steps at which texels last touched a medium
  int channels = 1;
  std::size_t plane = 0;    // texels per plane
  float clear_since = 0.0f;  // the latest touch a texel may have
  vec2 map_center{0.0f};     // the slab mapping (SlabMapping) and the tap's offset w
  float map_scale = 1.0f;
  vec2 w{0.0f};
};

// Pixels (px, py) of the lanes in `on`: those whose light crossed no medium
// in the last slab and whose four texels (a bilinear read, clamp-to-edge)
// have been clear of any medium since `clear_since` take the carried light,
// channel c into out[c * L::kWidth + lane]; returns them.
template <class L>
PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Mask read_carried_lanes(const CarriedReadView& r, typename L::Float px,
                                                                      float py, typename L::Mask on, float* out) {
  using F = typename L::Float;
  using I = typename L::Int;
  using X = typename L::Index;
  const CarriedGrid& g = r.grid;
  const F from_x = r.map_center.x + r.map_scale * (px - r.map_center.x) + r.w.x;  // where its light came from
  const F from_y(r.map_center.y + r.map_scale * (py - r.map_center.y) + r.w.y);
  typename L::Mask free = on & !r.medium.touches<L>(from_x, from_y);
  if (none(free)) return free;
  const F fx = g.grid_center.x + ((px - g.center.x) - g.offset.x) / g.scale - 0.5f;
  const F fy(g.grid_center.y + ((py - g.center.y) - g.offset.y) / g.scale - 0.5f);
  const F fx0 = floor(fx), fy0 = floor(fy);
  const F tx = fx - fx0, ty = fy - fy0;
  const I ix0 = to_int(fx0), iy0 = to_int(fy0);
  const I x0 = max(I(0), min(ix0, I(g.width - 1))), x1 = max(I(0), min(ix0 + I(1), I(g.width - 1)));
  const I r0 = I(g.width) * max(I(0), min(iy0, I(g.height - 1)));
  const I r1 = I(g.width) * max(I(0), min(iy0 + I(1), I(g.height - 1)));
  const X i00(r0 + x0), i10(r0 + x1), i01(r1 + x0), i11(r1 + x1);
  const F newest = max(max(gather(r.touched, i00), gather(r.touched, i10)),
                       max(gather(r.touched, i01), gather(r.touched, i11)));
  free = free & !(newest > F(r.clear_since));
  if (none(free)) return free;
  for (int c = 0; c < r.channels; ++c) {
    const float* v = r.texels + std::size_t(c) * r.plane;
    const F value = (1.0f - ty) * ((1.0f - tx) * gather(v, i00) + tx * gather(v, i10)) +
                    ty * ((1.0f - tx) * gather(v, i01) + tx * gather(v, i11));
    L::store(value, out + c * L::kWidth);
  }
  return free;
}

// Row y of CarriedLights::propagate, L::kWidth pixels at a time: the carried
// light into `incoming` (`channels` planes of frame_plane pixels) where it
// applies, needs[x] = 1 where pixel x must take the re-sampled light instead.
// Returns the pixels that took the carried light.
template <class L>
PENUMBRA_HD std::uint64_t read_carried_row(const CarriedReadView& r, int width, int y, std::size_t frame_plane,
                                           float* incoming, std::uint8_t* needs) {
  constexpr int W = L::kWidth;
  static constexpr float kCentres[16] = {0.5f, 1.5f, 2.5f,  3.5f,  4.5f,  5.5f,  6.5f,  7.5f,
                                         8.5f, 9.5f, 10.5f, 11.5f, 12.5f, 13.5f, 14.5f, 15.5f};
  static_assert(W <= 16, "pixel centres for up to 16 lanes");
  float out[CarriedReadView::kMaxChannels * W];
  const float py = float(y) + 0.5f;
  const std::size_t row = std::size_t(width) * std::size_t(y);
  std::uint64_t taken = 0;
  for (int x = 0; x < width; x += W) {
    const int count = width - x < W ? width - x : W;
    const typename L::Float px = typename L::Float(float(x)) + L::load(kCentres);
    const std::uint32_t free = L::bits(read_carried_lanes<L>(r, px, py, first_lanes<L>(count), out));
    for (int i = 0; i < count; ++i) {
      if ((free >> i) & 1u) {
        for (int c = 0; c < r.channels; ++c) {
          incoming[std::size_t(c) * frame_plane + row + std::size_t(x + i)] = out[c * W + i];
        }
        ++taken;
      } else {
        needs[x + i] = 1;
      }
    }
  }
  return taken;
}

// The row read as packets of Target. Defined only in the SIMD units of
// Target (convolution_packets.cpp).
template <SimdTarget Target>
std::uint64_t read_carried_row_packets(const CarriedReadView& r, int width, int y, std::size_t frame_plane,
                                       float* incoming, std::uint8_t* needs);
using CarriedRowRead = std::uint64_t (*)(const CarriedReadView&, int, int, std::size_t, float*, std::uint8_t*);

// The carried grids of one frame's zero-variance lights.
class CarriedLights {
 public:
  // `carried[l]`: light l is carried (its kernel has one tap); `min_age`:
  // the slabs a texel must have travelled clear of any medium before a pixel
  // takes its light.
  void start(int frame_width, int frame_height, int channels, float min_scale, int min_age,
             const std::vector<char>& carried);
  bool carries(int l) const { return std::size_t(l) < carried_.size() && carried_[std::size_t(l)]; }
  const CarriedGrid& grid(int l) const { return grids_[std::size_t(l)]; }

  // Slab k > 0, light l: `medium` is slab k - 1's mask and extinction (as
  // many channels as the lights), `path` the light's path length through a
  // slab. Texels whose crossing of slab k - 1 touched the medium are
  // attenuated by exp(-path extinction), read bilinearly; then the grid
  // follows its rays into slab k (`mapping`, w: convolve_texel_mapped's).
  void advance(int l, float path, const MediumMask& medium, const SlabMapping& mapping, vec2 w);
  // The same where the volume is the only medium: a texel whose crossing of
  // slab k - 1 touched the medium is attenuated by exp(-path
  // extinction_at(p)), the volume's extinction toward the light (per unit
  // path) sampled on the texel's own ray, p its frame pixel coordinates on
  // slab k - 1. The mask's extinction planes are not read.
  template <class Extinction>
  void advance_sampled(int l, float path, const MediumMask& medium, const SlabMapping& mapping, vec2 w,
                       const Extinction& extinction_at);
  // Then the light entering slab k at every pixel, into `incoming`
  // (`channels` planes): the carried light where it crossed no medium in
  // slab k - 1 (and the texels read have been clear for `min_age` slabs),
  // elsewhere `out` re-sampled by the slab step (convolve_texel_mapped with
  // the single-tap `kernel`, as convolve_slab). Returns the number of pixels
  // that took the carried light.
  std::uint64_t propagate(int l, const SlabFrame& frame, const SlabKernel& kernel, const float* out, float* incoming,
                          const MediumMask& medium, const SlabMapping& mapping, vec2 w) const;
  // The carried light entering slab k at frame pixel (x, y) (after
  // advance(l, ...) for slab k), for slabs past every medium: there the mask
  // is empty and every texel has been clear for at least min_age slabs, so
  // propagate would give every pixel this read. The caller ensures that
  // (SlabRenderer's empty tail); the texels' age is not checked here.
  vec3 read_clear(int l, float px, float py, const MediumMask& medium, const SlabMapping& mapping, vec2 w) const;

  std::uint64_t bytes() const { return (texels_.size() + transmittance_.size()) * sizeof(float); }
  // What propagate reads the carried light as: the active SIMD target when
  // a light is carried and this build has its packets, else Scalar.
  SimdTarget target() const;
  static constexpr float kNeverTouched = -1e6f;  // the step a texel that never touched a medium touched it

 private:
  // `channels_` planes of light, then one of the step (advance) at which each
  // texel last touched a medium (re-bases copy it with the light).
  float* texels(int l, int half);
  // Counts the step, then multiplies each texel whose crossing of the last
  // slab touched `medium` (and marks it touched now) by transmittance(p,
  // out): `channels_` values into out, p the texel's frame pixel coordinates.
  template <class Transmittance>
  void attenuate_touched(int l, const MediumMask& medium, const Transmittance& transmittance);
  // The grid follows its rays into the next slab (and is re-based if needed).
  void move(int l, const SlabMapping& mapping, vec2 w);
  CarriedReadView read_view(int l, const MediumMask& medium, const SlabMapping& mapping, vec2 w) const;

  int frame_width_ = 0, frame_height_ = 0, channels_ = 1, min_age_ = 1;
  float min_scale_ = 1.0f;
  std::vector<char> carried_;
  std::vector<CarriedGrid> grids_;
  std::vector<int> half_;               // which half of each light's pair holds its texels
  std::vector<int> steps_;              // per light, advances so far
  std::vector<std::size_t> base_;       // per light, its pair's first float
  std::vector<float> texels_;
  std::vector<float> transmittance_;  // the last slab's, per channel and frame pixel (advance's scratch)
};

template <class Transmittance>
void CarriedLights::attenuate_touched(int l, const MediumMask& medium, const Transmittance& transmittance) {
  const CarriedGrid& g = grids_[std::size_t(l)];
  float* t = texels(l, half_[std::size_t(l)]);
  const std::size_t plane = std::size_t(g.width) * std::size_t(g.height);
  const float step = float(++steps_[std::size_t(l)]);
  if (!medium.any()) return;
  parallel_for(0, g.height, [&](std::int64_t first, std::int64_t last) {
    float through[CarriedReadView::kMaxChannels];
    for (std::int64_t y = first; y < last; ++y) {
      for (int x = 0; x < g.width; ++x) {
        const vec2 p = g.position(x, int(y));
        if (!medium.touches(p)) continue;
        const std::size_t i = std::size_t(x) + std::size_t(g.width) * std::size_t(y);
        t[std::size_t(channels_) * plane + i] = step;
        transmittance(p, through);
        for (int c = 0; c < channels_; ++c) t[std::size_t(c) * plane + i] *= through[c];
      }
    }
  });
}

template <class Extinction>
void CarriedLights::advance_sampled(int l, float path, const MediumMask& medium, const SlabMapping& mapping, vec2 w,
                                    const Extinction& extinction_at) {
  attenuate_touched(l, medium, [&](vec2 p, float* out) {
    const float sigma = extinction_at(p);
    const float through = sigma > 0.0f ? exp_nonpositive(-path * sigma) : 1.0f;
    for (int c = 0; c < channels_; ++c) out[c] = through;
  });
  move(l, mapping, w);
}

}  // namespace penumbra

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
// the same light without re-sampling where nothing attenuated it:
//   - a texel whose crossing of a slab touched the medium (any of the four
//     pixels around it has optical depth there) takes the light leaving that
//     slab from the pixel grid (one bilinear read); elsewhere it keeps its
//     value as it moves;
//   - a pixel takes its light from the carried grid (one bilinear read)
//     instead of the re-sampled value when its light crossed no medium in the
//     last slab (the four pixels around where it came from have none) and
//     the four texels it reads have not touched a medium for `min_age`
//     slabs (about a pixel of the light's sideways travel).
// So light re-samples every slab only while it crosses a medium and for
// about a pixel beyond it; across empty space to a receiver farther away it
// is read twice, leaving the occluder and arriving. Re-sampling every slab
// left hard shadows 2.4-3.5 px wide where shadow-rays draws 0.9-1.5 px (the
// blur grows with the slab count).
// The age condition keeps the pixel grid's light next to a medium: a texel
// that took its light between a dense column and a clear one holds a mix of
// both, and read by the clear pixel beside a dense surface it would darken
// it (a dense box's lit faces: 0.374 against the path tracer's 0.422, 0.411
// re-sampled), where the re-sampled light has come down the pixel's own
// column.
//
// Two re-bases keep the grid over the frame: an integer shift of the texels
// (an exact copy) whenever |offset| passes a few texels, so the grid follows
// light that drifts sideways; and a re-sampling onto the pixel grid when a
// perspective camera has shrunk it (scale = z_0 / z_k) below the scale it was
// sized for (at most one per halving of scale; never with an orthographic
// camera). Texels beyond the grid's edge are its edge texels (clamp-to-edge),
// as for the pixel grid's buffers.
#include "penumbra/base/math.h"
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

// Which frame positions have a medium among the four pixels a bilinear read
// there takes (clamp-to-edge), for one slab: the slab loop flags the pixels
// where the slab has optical depth, build() dilates the flags once per slab,
// and a query is one lookup.
class MediumMask {
 public:
  void resize(int frame_width, int frame_height);  // all clear
  std::uint8_t* flags() { return any_.data(); }     // per pixel: 1 where the slab has a medium
  void build();
  // p in frame pixel coordinates, pixel centres at +0.5.
  bool touches(vec2 p) const {
    const int x0 = int(std::floor(glm::clamp(p.x - 0.5f, -1.0f, float(width_ - 1))));
    const int y0 = int(std::floor(glm::clamp(p.y - 0.5f, -1.0f, float(height_ - 1))));
    return mask_[std::size_t(x0 + 1) + std::size_t(width_ + 1) * std::size_t(y0 + 1)] != 0;
  }

 private:
  int width_ = 0, height_ = 0;
  std::vector<std::uint8_t> any_;   // the flags
  std::vector<std::uint8_t> mask_;  // (width + 1) x (height + 1): entry (x0 + 1, y0 + 1) for pixels x0..x0+1, y0..y0+1
};

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

  // Slab k > 0, light l: `out` is the light leaving slab k - 1 on the pixel
  // grid (`channels` planes of frame pixels) and `medium` that slab's mask.
  // Texels whose crossing of slab k - 1
  // touched the medium take their light from `out`; then the grid follows
  // its rays into slab k (`mapping`, w: convolve_texel_mapped's).
  void advance(int l, const float* out, const MediumMask& medium, const SlabMapping& mapping, vec2 w);
  // Then the light entering slab k at every pixel, into `incoming`
  // (`channels` planes): the carried light where it crossed no medium in
  // slab k - 1 (and the texels read have been clear for `min_age` slabs),
  // elsewhere `out` re-sampled by the slab step (convolve_texel_mapped with
  // the single-tap `kernel`, as convolve_slab). Returns the number of pixels
  // that took the carried light.
  std::uint64_t propagate(int l, const SlabFrame& frame, const SlabKernel& kernel, const float* out, float* incoming,
                          const MediumMask& medium, const SlabMapping& mapping, vec2 w) const;

  std::uint64_t bytes() const { return texels_.size() * sizeof(float); }
  static constexpr float kNeverTouched = -1e6f;  // the step a texel that never touched a medium touched it

 private:
  // `channels_` planes of light, then one of the step (advance) at which each
  // texel last touched a medium (re-bases copy it with the light).
  float* texels(int l, int half);

  int frame_width_ = 0, frame_height_ = 0, channels_ = 1, min_age_ = 1;
  float min_scale_ = 1.0f;
  std::vector<char> carried_;
  std::vector<CarriedGrid> grids_;
  std::vector<int> half_;               // which half of each light's pair holds its texels
  std::vector<int> steps_;              // per light, advances so far
  std::vector<std::size_t> base_;       // per light, its pair's first float
  std::vector<float> texels_;
};

}  // namespace penumbra

#pragma once
// Light paths across a slab, taken slanted where they meet a surface (issue
// 23's slab rings).
//
// The slab loop keeps the light on the pixel grid of each slab's middle plane
// and moves it sideways from slab to slab (light_propagation.h); the light
// leaving pixel A's column was attenuated down that column. But its path
// crosses the slab [z0, z0 + e] sideways, a drift delta (pixels) from front
// to back, and where a surface is tilted to the slabs the path enters or
// leaves the medium at another depth than the column does. The covered depth
// is then off by about (surface depth - z0) * (slope . delta) / e, an error
// that repeats with every slab the surface passes: concentric rings on a
// sphere lit off the view axis, which a finer slab distance only shrinks.
// The same holds for a sample's own light within its slab.
//
// Some surfaces are known exactly: a mesh's (each pixel's ray crosses runs of
// depth inside a mesh, [h, g], in the layered depth image) and the volume's
// box and clip planes (the ray's interval inside them). Across a path's short
// sideways travel such a surface is taken as a plane, with the run ends'
// gradients over the neighbouring pixels, and the depth the path spends
// inside follows (slanted_inside_length). The slab renderer uses it three
// ways:
//   - the light leaving a slab is attenuated along each pixel's path through
//     the slab (attenuate), at the extinction the pixel's column sampled or,
//     where only the path meets the medium, its neighbours';
//   - a sample's light crosses the depth inside along the light's path from
//     the slab's front to the back of its part of the slab (inside);
//   - and is read where the ray through the part's middle crossed the slab's
//     plane (drift), not at the pixel.
// Only scenes with a mesh take this path (the box too, so that a volume and a
// mesh of the same shape render alike); volume-only scenes keep the column
// model, as does the inside of any volume (its iso-surfaces are not known).
// docs/convolution.md, "Slanted light paths".
#include "penumbra/base/math.h"
#include "penumbra/techniques/convolution/layered_depth_image.h"
#include "penumbra/techniques/convolution/light_propagation.h"

#include <cstdint>
#include <vector>

namespace penumbra {

// The depth a straight path spends inside a run over depths [z0, z0 + span]:
// the run's ends are [h, g] at the path's middle depth and change by dh, dg
// from the path's front to its back (the surfaces as planes across its
// sideways travel). With dh = dg = 0 it is the column's covered depth.
PENUMBRA_HD inline float slanted_inside_length(float z0, float span, float h, float g, float dh, float dg) {
  float lo = 0.0f, hi = 1.0f;  // the path's fraction u, at depth z0 + u span
  // Keeps the u of [lo, hi] where c0 + c1 u >= 0.
  const auto keep = [&](float c0, float c1) {
    if (c1 == 0.0f) {
      if (c0 < 0.0f) hi = lo;
    } else if (c1 > 0.0f) {
      lo = glm::max(lo, -c0 / c1);
    } else {
      hi = glm::min(hi, -c0 / c1);
    }
  };
  keep(z0 - h + 0.5f * dh, span - dh);  // behind the entering surface, h + (u - 1/2) dh
  keep(g - 0.5f * dg - z0, dg - span);  // in front of the leaving one, g + (u - 1/2) dg
  return span * glm::max(hi - lo, 0.0f);
}

// Each pixel's runs of depth inside a medium, front to back, and the one
// nearest the current slab.
class SurfaceRuns {
 public:
  // From the layered depth image: depth inside any mesh (frame pixel (x, y)
  // is LDI pixel (x + shift, y + shift)). `version` names the image (its
  // build count): the runs of an unchanged image are kept, only the cursors
  // start again.
  void from_ldi(const LdiView& ldi, int width, int height, int shift, int version);
  // One run per pixel; a run with h > g is none.
  void from_intervals(const std::vector<vec2>& runs, int width, int height);
  // Each pixel's run nearest the slab [z0, z0 + e] (overlapping it, else the
  // closest; ends more than 4 e off are clamped to that, so that a far end
  // and a crease or jump in it do not tilt the plane), and its ends'
  // gradients.
  void enter_slab(float z0, float e);
  bool any(std::size_t i) const { return current_[i].x <= current_[i].y; }
  // The pixels with any run, in order.
  const std::vector<std::uint32_t>& pixels_with_runs() const { return with_runs_; }
  // The depth inside on a path over [z0, to] whose sideways travel per unit
  // depth is d (pixels), crossing pixel i's ray at depth `through`.
  float inside(std::size_t i, vec2 d, float z0, float through, float to) const {
    const vec2 r = current_[i];
    const float span = to - z0;
    if (r.x > r.y || !(span > 0.0f)) return 0.0f;
    const vec4 grad = gradients_[i];  // (h x, h y, g x, g y)
    const float slope_h = d.x * grad.x + d.y * grad.y, slope_g = d.x * grad.z + d.y * grad.w;
    const float middle = z0 + 0.5f * span - through;  // the path's middle depth, from where it crosses the ray
    return slanted_inside_length(z0, span, r.x + middle * slope_h, r.y + middle * slope_g, span * slope_h,
                                 span * slope_g);
  }

 private:
  void start_cursors();
  int width_ = 0, height_ = 0;
  int shift_ = -1, version_ = -1;  // the image the runs came from (from_ldi)
  std::vector<std::uint32_t> offsets_;  // per pixel, its runs in runs_ (CSR)
  std::vector<vec2> runs_;
  std::vector<std::uint32_t> cursor_;  // per pixel, its run nearest the slab (slabs come front to back)
  std::vector<vec2> current_;          // that run, clamped; (1, 0): none
  std::vector<vec4> gradients_;        // its ends' gradients per pixel
  std::vector<std::uint32_t> with_runs_;  // the pixels with any run
};

// The slab renderer's slanted paths: the meshes' runs, the volume's box, the
// lights' sideways travel, and what each pixel's column crossed in the slab.
class SlantedPaths {
 public:
  // Once per frame. `ldi`: the meshes' layered depth image (null: none),
  // `ldi_version` its build count;
  // `box`: per pixel, the ray's depth interval inside the volume's box and
  // clip planes, up to its plane (empty where the volume has no extinction).
  void start(const LdiView* ldi, int shift, int ldi_version, const std::vector<vec2>& box, int width, int height);
  // Before the pixel loop of the slab whose middle plane lies at depth z
  // (`light_means`: e mu per light, world units, light_propagation.h).
  void enter_slab(const SlabFrame& frame, float z, const std::vector<vec2>& light_means);

  // Light l's sideways travel (pixels) across the slab at pixel (x, y).
  vec2 drift(int l, int x, int y) const {
    const vec2 pixel(float(x) + 0.5f, float(y) + 0.5f);
    return (1.0f - map_.scale) * (pixel - map_.center) + drift_offset_[std::size_t(l)];
  }
  // The depth inside a mesh (the volume's box) on light l's path from the
  // slab's front to depth `to`, the path crossing pixel (x, y)'s ray at depth
  // `through`.
  float inside_mesh(int l, int x, int y, float through, float to) const {
    return meshes_on_ ? meshes_.inside(index(x, y), drift(l, x, y) / e_, z0_, through, to) : 0.0f;
  }
  float inside_box(int l, int x, int y, float through, float to) const {
    return box_.inside(index(x, y), drift(l, x, y) / e_, z0_, through, to);
  }

  // What the pixel loop leaves for attenuate(): whether pixel i attenuates
  // its light (`live`), and the extinction where its column crosses a mesh
  // (`mesh_sigma`, per channel) or the volume (`volume_sigma`, its sample's).
  void clear(std::size_t i, bool live) {
    live_[i] = live;
    covered_[i] = 0;
    mesh_sigma_[i] = vec3(0.0f);
    volume_sigma_[i] = 0.0f;
  }
  void record_mesh(std::size_t i, vec3 sigma) {
    covered_[i] |= 1;
    mesh_sigma_[i] = sigma;
  }
  void record_volume(std::size_t i, float sigma) {
    covered_[i] |= 2;
    volume_sigma_[i] = sigma;
  }
  // After the pixel loop: multiplies light l's buffer planes (planes[l *
  // channels + c]) by each live pixel's transmittance along its path across
  // the slab; flags has_medium (if given) where the path met a medium.
  void attenuate(float* const* planes, int light_count, int channels, const std::vector<float>& light_path,
                 std::uint8_t* has_medium) const;

 private:
  std::size_t index(int x, int y) const { return std::size_t(x) + std::size_t(width_) * std::size_t(y); }
  int width_ = 0, height_ = 0;
  float z0_ = 0.0f, e_ = 1.0f;
  bool meshes_on_ = false;
  SurfaceRuns meshes_, box_;
  SlabMapping map_;
  std::vector<vec2> drift_offset_;
  std::vector<std::uint32_t> active_;  // the pixels with a run of either kind
  std::vector<std::uint8_t> live_, covered_;  // covered_: 1 a mesh, 2 the volume
  std::vector<vec3> mesh_sigma_;
  std::vector<float> volume_sigma_;
};

}  // namespace penumbra

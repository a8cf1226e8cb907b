#include "penumbra/techniques/convolution/carried_light.h"

#include "penumbra/base/error.h"
#include "penumbra/base/parallel.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <vector>

namespace penumbra {

CarriedGrid carried_grid(int frame_width, int frame_height, float min_scale) {
  // Half the grid, times the smallest scale, must reach half the frame, plus
  // the offset it may run up before a shift and 2 texels of bilinear support.
  const auto texels = [min_scale](int pixels) {
    return 2 * int(std::ceil(0.5f * float(pixels) / min_scale + float(CarriedGrid::kShiftTexels) + 2.5f));
  };
  CarriedGrid g;
  g.width = texels(frame_width);
  g.height = texels(frame_height);
  g.center = vec2(0.5f * float(frame_width), 0.5f * float(frame_height));
  g.grid_center = vec2(0.5f * float(g.width), 0.5f * float(g.height));
  return g;
}

void advance_carried_grid(CarriedGrid& grid, const SlabMapping& mapping, vec2 w) {
  grid.scale /= mapping.scale;
  grid.offset = (grid.offset - w) / mapping.scale;
}

void resample_carried_grid(CarriedGrid& grid, const float* from, float* to, int planes) {
  const std::size_t plane = std::size_t(grid.width) * std::size_t(grid.height);
  const CarriedGrid old = grid;
  grid.scale = 1.0f;
  grid.offset = vec2(0.0f);
  parallel_for(0, grid.height, [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t y = first; y < last; ++y) {
      for (int x = 0; x < grid.width; ++x) {
        const vec2 t = old.texel_of(grid.position(x, int(y)));
        for (int c = 0; c < planes; ++c) {
          to[std::size_t(c) * plane + std::size_t(x) + std::size_t(grid.width) * std::size_t(y)] =
              read_buffer_sharp(from + std::size_t(c) * plane, grid.width, grid.height, t);
        }
      }
    }
  });
}

ivec2 shift_carried_grid(CarriedGrid& grid, const float* from, float* to, int planes) {
  // Texel x of the shifted grid is texel x + n of this one, whose centre is
  // scale n further along: offset + scale n stays within half a texel.
  const vec2 drift = grid.offset / grid.scale;  // texels
  if (glm::max(std::abs(drift.x), std::abs(drift.y)) <= float(CarriedGrid::kShiftTexels)) return ivec2(0);
  const ivec2 n(int(std::lround(-drift.x)), int(std::lround(-drift.y)));
  const std::size_t plane = std::size_t(grid.width) * std::size_t(grid.height);
  grid.offset += grid.scale * vec2(n);
  parallel_for(0, grid.height, [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t y = first; y < last; ++y) {
      const int sy = glm::clamp(int(y) + n.y, 0, grid.height - 1);
      for (int x = 0; x < grid.width; ++x) {
        const int sx = glm::clamp(x + n.x, 0, grid.width - 1);
        for (int c = 0; c < planes; ++c) {
          to[std::size_t(c) * plane + std::size_t(x) + std::size_t(grid.width) * std::size_t(y)] =
              from[std::size_t(c) * plane + std::size_t(sx) + std::size_t(grid.width) * std::size_t(sy)];
        }
      }
    }
  });
  return n;
}

void MediumMask::resize(int frame_width, int frame_height, int channels) {
  width_ = frame_width;
  height_ = frame_height;
  any_.assign(std::size_t(frame_width) * std::size_t(frame_height), 0);
  extinction_.assign(std::size_t(channels) * any_.size(), 0.0f);
  mask_.assign(std::size_t(frame_width + 1) * std::size_t(frame_height + 1), 0);
  any_set_ = false;
}

void MediumMask::build() {
  const int w = width_, h = height_;
  // Entry (x0 + 1, y0 + 1): pixels x0, x0 + 1 and y0, y0 + 1, clamped.
  parallel_for(-1, h, [&](std::int64_t first, std::int64_t last) {
    for (int y0 = int(first); y0 < int(last); ++y0) {
      const std::uint8_t* r0 = any_.data() + std::size_t(w) * std::size_t(glm::max(y0, 0));
      const std::uint8_t* r1 = any_.data() + std::size_t(w) * std::size_t(glm::min(y0 + 1, h - 1));
      std::uint8_t* m = mask_.data() + std::size_t(w + 1) * std::size_t(y0 + 1);
      m[0] = r0[0] | r1[0];
      for (int x0 = 0; x0 < w - 1; ++x0) m[x0 + 1] = r0[x0] | r0[x0 + 1] | r1[x0] | r1[x0 + 1];
      m[w] = r0[w - 1] | r1[w - 1];
    }
  });
  any_set_ = std::any_of(any_.begin(), any_.end(), [](std::uint8_t f) { return f != 0; });
}

void CarriedLights::start(int frame_width, int frame_height, int channels, float min_scale, int min_age,
                          const std::vector<char>& carried) {
  if (channels < 1 || channels > CarriedReadView::kMaxChannels) {
    throw InvalidArgument("channels", "carried light grids hold 1 to 3 colour channels");
  }
  min_age_ = min_age;
  frame_width_ = frame_width;
  frame_height_ = frame_height;
  channels_ = channels;
  min_scale_ = min_scale;
  carried_ = carried;
  const CarriedGrid g = carried_grid(frame_width, frame_height, min_scale);
  const std::size_t plane = std::size_t(g.width) * std::size_t(g.height);
  grids_.assign(carried.size(), g);
  half_.assign(carried.size(), 0);
  steps_.assign(carried.size(), 0);
  base_.assign(carried.size(), 0);
  std::size_t floats = 0;
  for (std::size_t l = 0; l < carried.size(); ++l) {
    base_[l] = floats;
    if (carried[l]) floats += 2 * std::size_t(channels + 1) * plane;
  }
  texels_.assign(floats, 1.0f);  // unoccluded on the first slab, as the pixel grid's buffers
  for (std::size_t l = 0; l < carried.size(); ++l) {  // and no medium touched yet
    if (!carried[l]) continue;
    for (int half = 0; half < 2; ++half) {
      float* touched = texels(int(l), half) + std::size_t(channels) * plane;
      std::fill(touched, touched + plane, kNeverTouched);
    }
  }
}

float* CarriedLights::texels(int l, int half) {
  const CarriedGrid& g = grids_[std::size_t(l)];
  return texels_.data() + base_[std::size_t(l)] +
         std::size_t(half) * std::size_t(channels_ + 1) * std::size_t(g.width) * std::size_t(g.height);
}

void CarriedLights::advance(int l, float path, const MediumMask& medium, const SlabMapping& mapping, vec2 w) {
  const std::size_t frame_plane = std::size_t(frame_width_) * std::size_t(frame_height_);
  if (medium.any()) {  // the slab's transmittance per pixel, for the texels' bilinear reads
    transmittance_.resize(std::size_t(channels_) * frame_plane);
    parallel_for(0, frame_height_, [&](std::int64_t first, std::int64_t last) {
      for (int c = 0; c < channels_; ++c) {
        const float* extinction = medium.extinction(c);
        float* out = transmittance_.data() + std::size_t(c) * frame_plane;
        const std::size_t begin = std::size_t(first) * std::size_t(frame_width_);
        const std::size_t end = std::size_t(last) * std::size_t(frame_width_);
        for (std::size_t i = begin; i < end; ++i) {
          out[i] = extinction[i] > 0.0f ? exp_nonpositive(-path * extinction[i]) : 1.0f;
        }
      }
    });
  }
  attenuate_touched(l, medium, [&](vec2 p, float* out) {
    for (int c = 0; c < channels_; ++c) {
      out[c] = read_buffer(transmittance_.data() + std::size_t(c) * frame_plane, frame_width_, frame_height_, p);
    }
  });
  move(l, mapping, w);
}

void CarriedLights::move(int l, const SlabMapping& mapping, vec2 w) {
  CarriedGrid& g = grids_[std::size_t(l)];
  int& half = half_[std::size_t(l)];
  float* t = texels(l, half);
  advance_carried_grid(g, mapping, w);
  if (g.scale < min_scale_) {
    resample_carried_grid(g, t, texels(l, 1 - half), channels_ + 1);
    half = 1 - half;
  } else if (shift_carried_grid(g, t, texels(l, 1 - half), channels_ + 1) != ivec2(0)) {
    half = 1 - half;
  }
}

namespace {

// The row read as packets on the active SIMD target, or nullptr.
CarriedRowRead carried_row_packets() {
  return simd_unit_function(active_simd_target(), []<SimdTarget T>() { return &read_carried_row_packets<T>; });
}

}  // namespace

CarriedReadView CarriedLights::read_view(int l, const MediumMask& medium, const SlabMapping& mapping, vec2 w) const {
  const CarriedGrid& g = grids_[std::size_t(l)];
  const std::size_t plane = std::size_t(g.width) * std::size_t(g.height);
  CarriedReadView r;
  r.medium = medium.view();
  r.grid = g;
  r.texels = texels_.data() + base_[std::size_t(l)] +
             std::size_t(half_[std::size_t(l)]) * std::size_t(channels_ + 1) * plane;
  r.touched = r.texels + std::size_t(channels_) * plane;
  r.channels = channels_;
  r.plane = plane;
  r.clear_since = float(steps_[std::size_t(l)] - min_age_);
  r.map_center = mapping.center;
  r.map_scale = mapping.scale;
  r.w = w;
  return r;
}

vec3 CarriedLights::read_clear(int l, float px, float py, const MediumMask& medium, const SlabMapping& mapping,
                               vec2 w) const {
  CarriedReadView r = read_view(l, medium, mapping, w);
  r.clear_since = kInfinity;
  float out[CarriedReadView::kMaxChannels] = {1.0f, 1.0f, 1.0f};
  read_carried_lanes<ScalarLanes>(r, px, py, true, out);
  return channels_ == 1 ? vec3(out[0]) : vec3(out[0], out[1], out[2]);
}

SimdTarget CarriedLights::target() const {
  bool any = false;
  for (const char c : carried_) any = any || c;
  return any && carried_row_packets() && channels_ <= CarriedReadView::kMaxChannels ? active_simd_target()
                                                                                   : SimdTarget::Scalar;
}

std::uint64_t CarriedLights::propagate(int l, const SlabFrame& frame, const SlabKernel& kernel, const float* out,
                                       float* incoming, const MediumMask& medium, const SlabMapping& mapping,
                                       vec2 w) const {
  const CarriedReadView r = read_view(l, medium, mapping, w);
  const std::size_t plane = r.plane;
  const std::size_t frame_plane = std::size_t(frame_width_) * std::size_t(frame_height_);
  // Packets need 32-bit gather offsets into the grid.
  const CarriedRowRead packets =
      plane < (std::size_t(1) << 31) && channels_ <= CarriedReadView::kMaxChannels ? carried_row_packets() : nullptr;
  std::atomic<std::uint64_t> free{0};
  parallel_for(0, frame_height_, [&](std::int64_t first, std::int64_t last) {
    std::vector<std::uint8_t> needs(static_cast<std::size_t>(frame_width_));
    std::uint64_t count = 0;
    for (std::int64_t y = first; y < last; ++y) {
      std::fill(needs.begin(), needs.end(), std::uint8_t(0));
      count += packets ? packets(r, frame_width_, int(y), frame_plane, incoming, needs.data())
                       : read_carried_row<ScalarLanes>(r, frame_width_, int(y), frame_plane, incoming, needs.data());
      // Elsewhere the light re-sampled by the slab step.
      for (int x = 0; x < frame_width_; ++x) {
        if (!needs[std::size_t(x)]) continue;
        const std::size_t i = std::size_t(x) + std::size_t(frame_width_) * std::size_t(y);
        for (int c = 0; c < channels_; ++c) {
          incoming[std::size_t(c) * frame_plane + i] =
              convolve_texel_mapped(frame, mapping, kernel, out + std::size_t(c) * frame_plane, x, int(y));
        }
      }
    }
    free.fetch_add(count, std::memory_order_relaxed);
  });
  return free.load();
}

}  // namespace penumbra

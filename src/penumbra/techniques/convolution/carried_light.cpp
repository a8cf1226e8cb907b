#include "penumbra/techniques/convolution/carried_light.h"

#include "penumbra/base/parallel.h"

#include <atomic>
#include <cmath>

namespace penumbra {

CarriedGrid carried_grid(int frame_width, int frame_height, float min_scale) {
  // Half the grid, times the smallest scale, must reach half the frame plus
  // half a texel of offset and 2 texels of bilinear support.
  const auto texels = [min_scale](int pixels) {
    return 2 * int(std::ceil((0.5f * float(pixels) + 2.5f) / min_scale));
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
  const ivec2 n(int(std::lround(-grid.offset.x / grid.scale)), int(std::lround(-grid.offset.y / grid.scale)));
  if (n == ivec2(0)) return n;
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

bool touches_medium(const float* depth, int channels, int frame_width, int frame_height, vec2 p) {
  const int x0 = int(std::floor(glm::clamp(p.x - 0.5f, -2.0f, float(frame_width))));
  const int y0 = int(std::floor(glm::clamp(p.y - 0.5f, -2.0f, float(frame_height))));
  for (int j = 0; j < 2; ++j) {
    const std::size_t row = std::size_t(frame_width) * std::size_t(glm::clamp(y0 + j, 0, frame_height - 1));
    for (int i = 0; i < 2; ++i) {
      const float* d = depth + (row + std::size_t(glm::clamp(x0 + i, 0, frame_width - 1))) * std::size_t(channels);
      for (int c = 0; c < channels; ++c) {
        if (d[c] > 0.0f) return true;
      }
    }
  }
  return false;
}

void CarriedLights::start(int frame_width, int frame_height, int channels, float min_scale, int min_age,
                          const std::vector<char>& carried) {
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
      float* age = texels(int(l), half) + std::size_t(channels) * plane;
      std::fill(age, age + plane, kNeverTouched);
    }
  }
}

float* CarriedLights::texels(int l, int half) {
  const CarriedGrid& g = grids_[std::size_t(l)];
  return texels_.data() + base_[std::size_t(l)] +
         std::size_t(half) * std::size_t(channels_ + 1) * std::size_t(g.width) * std::size_t(g.height);
}

void CarriedLights::advance(int l, const float* out, const float* depth, const SlabMapping& mapping, vec2 w) {
  CarriedGrid& g = grids_[std::size_t(l)];
  int& half = half_[std::size_t(l)];
  float* t = texels(l, half);
  const std::size_t plane = std::size_t(g.width) * std::size_t(g.height);
  const std::size_t frame_plane = std::size_t(frame_width_) * std::size_t(frame_height_);
  parallel_for(0, g.height, [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t y = first; y < last; ++y) {
      for (int x = 0; x < g.width; ++x) {
        const vec2 p = g.position(x, int(y));
        float& age = t[std::size_t(channels_) * plane + std::size_t(x) + std::size_t(g.width) * std::size_t(y)];
        if (!touches_medium(depth, channels_, frame_width_, frame_height_, p)) {
          age = glm::min(age + 1.0f, kNeverTouched);
          continue;
        }
        age = 0.0f;
        for (int c = 0; c < channels_; ++c) {
          t[std::size_t(c) * plane + std::size_t(x) + std::size_t(g.width) * std::size_t(y)] =
              read_buffer(out + std::size_t(c) * frame_plane, frame_width_, frame_height_, p);
        }
      }
    }
  });
  advance_carried_grid(g, mapping, w);
  if (g.scale < min_scale_) {
    resample_carried_grid(g, t, texels(l, 1 - half), channels_ + 1);
    half = 1 - half;
  } else if (shift_carried_grid(g, t, texels(l, 1 - half), channels_ + 1) != ivec2(0)) {
    half = 1 - half;
  }
}

namespace {

// The least of the four texels a bilinear read at `texel` takes (clamp-to-edge).
float least_around(const float* plane, int width, int height, vec2 texel) {
  const int x0 = int(std::floor(glm::clamp(texel.x - 0.5f, -2.0f, float(width))));
  const int y0 = int(std::floor(glm::clamp(texel.y - 0.5f, -2.0f, float(height))));
  float least = CarriedLights::kNeverTouched;
  for (int j = 0; j < 2; ++j) {
    const std::size_t row = std::size_t(width) * std::size_t(glm::clamp(y0 + j, 0, height - 1));
    for (int i = 0; i < 2; ++i) least = glm::min(least, plane[row + std::size_t(glm::clamp(x0 + i, 0, width - 1))]);
  }
  return least;
}

}  // namespace

std::uint64_t CarriedLights::fill_free_pixels(int l, float* incoming, const float* depth, const SlabMapping& mapping,
                                              vec2 w) const {
  const CarriedGrid& g = grids_[std::size_t(l)];
  const std::size_t plane = std::size_t(g.width) * std::size_t(g.height);
  const std::size_t frame_plane = std::size_t(frame_width_) * std::size_t(frame_height_);
  const float* t =
      texels_.data() + base_[std::size_t(l)] + std::size_t(half_[std::size_t(l)]) * std::size_t(channels_ + 1) * plane;
  const float* age = t + std::size_t(channels_) * plane;
  std::atomic<std::uint64_t> free{0};
  parallel_for(0, frame_height_, [&](std::int64_t first, std::int64_t last) {
    std::uint64_t count = 0;
    for (std::int64_t y = first; y < last; ++y) {
      for (int x = 0; x < frame_width_; ++x) {
        const vec2 p(float(x) + 0.5f, float(y) + 0.5f);
        const vec2 from = mapping.center + mapping.scale * (p - mapping.center) + w;  // where its light came from
        if (touches_medium(depth, channels_, frame_width_, frame_height_, from)) continue;
        const vec2 texel = g.texel_of(p);
        if (least_around(age, g.width, g.height, texel) < float(min_age_)) continue;
        for (int c = 0; c < channels_; ++c) {
          incoming[std::size_t(c) * frame_plane + std::size_t(x) + std::size_t(frame_width_) * std::size_t(y)] =
              read_buffer(t + std::size_t(c) * plane, g.width, g.height, texel);
        }
        ++count;
      }
    }
    free.fetch_add(count, std::memory_order_relaxed);
  });
  return free.load();
}

}  // namespace penumbra

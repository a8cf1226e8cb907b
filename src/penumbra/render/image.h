#pragma once
// Image: linear float RGBA pixels, row 0 at the top. Colour is linear radiance;
// alpha is the accumulated opacity of what the ray hit (volume and planes).
#include "penumbra/base/math.h"

#include <cstddef>
#include <vector>

namespace penumbra {

class Image {
 public:
  Image() = default;
  // Checks the size against the memory budget; throws InvalidArgument for
  // negative sizes. A 0 x 0 image is allowed and empty.
  Image(int width, int height, vec4 fill = vec4(0.0f));

  int width() const { return width_; }
  int height() const { return height_; }
  bool empty() const { return pixels_.empty(); }
  std::size_t pixel_count() const { return pixels_.size(); }

  vec4& at(int x, int y) { return pixels_[static_cast<std::size_t>(y) * width_ + x]; }
  const vec4& at(int x, int y) const { return pixels_[static_cast<std::size_t>(y) * width_ + x]; }
  vec4* data() { return pixels_.data(); }
  const vec4* data() const { return pixels_.data(); }
  const std::vector<vec4>& pixels() const { return pixels_; }

 private:
  int width_ = 0;
  int height_ = 0;
  std::vector<vec4> pixels_;
};

}  // namespace penumbra

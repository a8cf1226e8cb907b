#include "penumbra/render/image.h"

#include "penumbra/base/error.h"
#include "penumbra/base/memory_budget.h"

#include <fmt/format.h>

namespace penumbra {

Image::Image(int width, int height, vec4 fill) : width_(width), height_(height) {
  if (width < 0 || height < 0) {
    throw InvalidArgument("size", fmt::format("image size must not be negative, got {}x{}", width, height));
  }
  check_memory_budget(fmt::format("a {}x{} image", width, height),
                      checked_product({std::uint64_t(width), std::uint64_t(height), sizeof(vec4)}));
  pixels_.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), fill);
}

}  // namespace penumbra

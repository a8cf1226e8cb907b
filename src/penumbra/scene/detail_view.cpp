#include "penumbra/scene/detail_view.h"

#include "penumbra/base/error.h"

#include <cmath>
#include <string>

namespace penumbra {

DetailResources::DetailResources(const DetailFunction& detail, const Box3& bounds) {
  if (!std::isfinite(detail.frequency))
    throw InvalidArgument("detail.frequency", "the detail frequency must be finite");
  if (detail.fractal.octaves < 0 || detail.fractal.octaves > 32)
    throw InvalidArgument("detail.octaves", "the detail needs 0 to 32 octaves, got " +
                                                std::to_string(detail.fractal.octaves));
  if (!std::isfinite(detail.fractal.lacunarity))
    throw InvalidArgument("detail.lacunarity", "the detail lacunarity must be finite");
  if (detail.type == DetailType::Texture && !detail.texture)
    throw InvalidArgument("detail.texture", "the texture volume '" + detail.texture_file + "' is not loaded");
  view_.type = detail.type;
  view_.frequency = detail.frequency;
  view_.fractal = detail.fractal;
  view_.time_dependent = detail.time_dependent;
  view_.value = detail.value;
  view_.bounds = bounds;
  noise_ = make_noise_table(detail.seed);
  if (detail.type == DetailType::Texture) texture_ = detail.texture;
}

DetailView DetailResources::view() const {
  DetailView v = view_;
  v.noise = &noise_;
  if (texture_) v.texture = texture_->view(0);
  return v;
}

}  // namespace penumbra

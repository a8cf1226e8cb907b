#pragma once
// IPSVI's early ray termination extension (Sundén et al. 2011, section 5.1).
// A viewing ray cannot simply stop at the ERT opacity: what it would skip may
// shadow the lines after it (Fig. 5). A cheap pre-pass at 1/kFactor of the
// image resolution (twice the step, no shading) records per ray
//   s_f  where the colour reaches the ERT opacity (+ two coarse steps), and
//   s_b  where the last non-empty macrocell run ends (nothing beyond it);
// then a sweep over the low-resolution image *toward* the light gives each
// ray the depth the rays after it need:
//   l_max(p_i) = min(s_b(p_i), max(s_f(p_i), l_max(p_{i-1})))
// with p_{i-1} the pixel on the next line away from the light along the
// light's image path through p_i. The paper compares ray lengths of two rays
// directly; here l_max(p_{i-1}) is first carried over to ray p_i along the
// light (the point of ray p_i closest to the light ray through the
// predecessor's exit point), which is the same when light crosses the view at
// right angles and stays right when it does not. The main pass stops a ray
// once its colour has terminated and it is past the largest l_max of the
// low-resolution pixels around it.
#include "penumbra/render/render_view.h"
#include "penumbra/techniques/ipsvi/sweep_plan.h"

#include <cstdint>
#include <vector>

namespace penumbra {

class EarlyTermination {
 public:
  static constexpr int kFactor = 4;

  // Runs the pre-pass and the sweep for `light` over the pixels of `rect`
  // (full resolution); `image_light` is the light's projection at full
  // resolution. Without ERT (threshold 1) every exit is +inf.
  void compute(const RenderView& view, const Light& light, const ImageLight& image_light, const PixelRect& rect);

  // The depth along pixel (x, y)'s ray after which the cache needs nothing.
  float exit_depth(int x, int y) const;

  std::uint64_t samples() const { return samples_; }
  std::uint64_t bytes() const;
  // The low-resolution maps, for tests and pictures.
  int width() const { return width_; }
  int height() const { return height_; }
  const std::vector<float>& front() const { return front_; }
  const std::vector<float>& back() const { return back_; }
  const std::vector<float>& needed() const { return needed_; }

 private:
  int width_ = 0, height_ = 0;
  float margin_ = 0.0f;
  bool active_ = false;
  std::vector<float> front_, back_, needed_, zone_;
  std::uint64_t samples_ = 0;
};

}  // namespace penumbra

#pragma once
// The render() of a technique that is a light-visibility function: one
// ray-casting pass over the image, shaded by the shared ScatteringLighting
// with the technique's Visibility (lighting.h). Techniques whose visibility
// needs the typed sampler (shadow-rays' marched shadow rays) call
// render_image directly.
#include "penumbra/render/lighting.h"
#include "penumbra/render/render_loop.h"

namespace penumbra {

template <class Visibility>
void render_lit(const RenderView& view, const Visibility& visibility, Shading shading, Image& image,
                RenderStats* stats = nullptr) {
  render_image(
      view, [&](const auto&) { return ScatteringLighting<Visibility>{&view, visibility, shading}; }, image, stats);
}

}  // namespace penumbra

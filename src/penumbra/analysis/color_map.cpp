#include "penumbra/analysis/color_map.h"

#include "penumbra/analysis/color_space.h"

#include <algorithm>
#include <cmath>
#include <span>

namespace penumbra {
namespace {

constexpr vec3 srgb8(int r, int g, int b) { return vec3(float(r) / 255.0f, float(g) / 255.0f, float(b) / 255.0f); }

// viridis sampled at 0, 0.25, 0.5, 0.75, 1 (#440154 #3b528b #21918c #5ec962
// #fde725). Five anchors keep L* monotonic (tested) at a fraction of the size
// of the 256-entry table.
constexpr vec3 kViridis[] = {srgb8(68, 1, 84), srgb8(59, 82, 139), srgb8(33, 145, 140), srgb8(94, 201, 98),
                             srgb8(253, 231, 37)};

// Moreland's cool-warm end points and neutral midpoint.
constexpr vec3 kCoolWarm[] = {srgb8(59, 76, 192), srgb8(221, 221, 221), srgb8(180, 4, 38)};

vec3 interpolate(std::span<const vec3> anchors, float t) {
  const float position = clamp01(t) * float(anchors.size() - 1);
  const std::size_t below = std::min(static_cast<std::size_t>(position), anchors.size() - 2);
  const float weight = position - float(below);
  return srgb_decode(glm::mix(anchors[below], anchors[below + 1], weight));
}

}  // namespace

vec3 map_color(ColorMap map, float t) {
  if (std::isnan(t)) return vec3(1.0f, 0.0f, 1.0f);
  switch (map) {
    case ColorMap::viridis:
      return interpolate(kViridis, t);
    case ColorMap::cool_warm:
      return interpolate(kCoolWarm, t);
  }
  return vec3(1.0f, 0.0f, 1.0f);
}

}  // namespace penumbra

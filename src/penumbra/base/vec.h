#pragma once
// Vector types and small numeric helpers shared by host and kernel code
// (math.h adds the lane-generic exp, log and pow; lanes.h the lane types).
#include "penumbra/base/hd.h"

#define GLM_FORCE_CTOR_INIT
#include <glm/glm.hpp>

#include <cstdint>
#include <limits>

namespace penumbra {

using glm::dvec3;
using glm::ivec2;
using glm::ivec3;
using glm::mat3;
using glm::mat4;
using glm::vec2;
using glm::vec3;
using glm::vec4;

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr float kInfinity = std::numeric_limits<float>::infinity();

PENUMBRA_HD inline float clamp01(float x) { return x < 0.0f ? 0.0f : (x > 1.0f ? 1.0f : x); }

// True for every float that is neither NaN nor +-infinity.
PENUMBRA_HD inline bool is_finite(float x) { return x - x == 0.0f; }

PENUMBRA_HD inline float max_component(vec3 v) { return glm::max(v.x, glm::max(v.y, v.z)); }
PENUMBRA_HD inline float min_component(vec3 v) { return glm::min(v.x, glm::min(v.y, v.z)); }

// Rec. 709 / sRGB luminance of a linear colour.
PENUMBRA_HD inline float luminance(vec3 c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

}  // namespace penumbra

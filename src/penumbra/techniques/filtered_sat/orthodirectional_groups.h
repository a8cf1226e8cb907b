#pragma once
// Which directional lights can share one light-aligned CSAT (Ament et al.
// 2014, section 4.2.2): lights along the six directions +-u, +-v, +-w of one
// orthonormal frame all read the same table, each with its cuboid along its
// own axis. Lights are taken in order; a light joins the first group whose
// frame it fits (parallel or antiparallel to one of its axes, or orthogonal
// to the single axis a group has so far), otherwise it starts a group. Two
// lights along the same direction share the table as well (same cuboid).
#include "penumbra/base/math.h"

#include <vector>

namespace penumbra {

// Directions closer than this (radians) to parallel or orthogonal count as such.
inline constexpr float kOrthodirectionalTolerance = 1e-3f;

struct OrthodirectionalGroup {
  vec3 axes[3];  // right-handed orthonormal frame (u, v, w) of the group's table
};

struct OrthodirectionalMember {
  int group = 0;
  int axis = 2;        // the frame axis the light lies along
  float sign = 1.0f;   // +1: toward the light is +axis; -1: toward the light is -axis
};

struct OrthodirectionalGrouping {
  std::vector<OrthodirectionalGroup> groups;
  std::vector<OrthodirectionalMember> members;  // one per input direction
};

// `to_light`: unit directions from the scene toward each light.
OrthodirectionalGrouping group_orthodirectional(const std::vector<vec3>& to_light);

}  // namespace penumbra

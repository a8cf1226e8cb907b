#include "penumbra/techniques/filtered_sat/orthodirectional_groups.h"

#include "penumbra/techniques/sat_common/cartesian_table_grid.h"

#include <cmath>

namespace penumbra {

OrthodirectionalGrouping group_orthodirectional(const std::vector<vec3>& to_light) {
  const float parallel = std::cos(kOrthodirectionalTolerance);
  const float orthogonal = std::sin(kOrthodirectionalTolerance);
  struct Pending {
    vec3 axes[3];
    int fixed = 1;  // axes fixed by lights so far: 1 (only axes[0]) or 3
  };
  std::vector<Pending> pending;
  OrthodirectionalGrouping out;
  for (const vec3& raw : to_light) {
    const vec3 d = glm::normalize(raw);
    OrthodirectionalMember member;
    bool placed = false;
    for (std::size_t g = 0; g < pending.size() && !placed; ++g) {
      Pending& p = pending[g];
      for (int a = 0; a < p.fixed && !placed; ++a) {
        const float c = glm::dot(d, p.axes[a]);
        if (std::abs(c) >= parallel) {
          member = {int(g), a, c > 0.0f ? 1.0f : -1.0f};
          placed = true;
        }
      }
      if (!placed && p.fixed == 1 && std::abs(glm::dot(d, p.axes[0])) <= orthogonal) {
        // The second axis is this light, made exactly orthogonal.
        p.axes[1] = glm::normalize(d - glm::dot(d, p.axes[0]) * p.axes[0]);
        p.axes[2] = glm::cross(p.axes[0], p.axes[1]);
        p.fixed = 3;
        member = {int(g), 1, 1.0f};
        placed = true;
      }
    }
    if (!placed) {
      Pending p;
      p.axes[0] = d;
      pending.push_back(p);
      member = {int(pending.size()) - 1, 0, 1.0f};
    }
    out.members.push_back(member);
  }
  for (const Pending& p : pending) {
    OrthodirectionalGroup group;
    if (p.fixed == 3) {
      for (int a = 0; a < 3; ++a) group.axes[a] = p.axes[a];
    } else {
      // One direction only: it becomes w, and u, v follow the world axes
      // where they can (a tighter table box for axis-aligned lights).
      group.axes[2] = p.axes[0];
      complete_frame(p.axes[0], group.axes[0], group.axes[1]);
    }
    out.groups.push_back(group);
  }
  for (OrthodirectionalMember& m : out.members) {
    if (pending[std::size_t(m.group)].fixed == 1) m.axis = 2;
  }
  return out;
}

}  // namespace penumbra

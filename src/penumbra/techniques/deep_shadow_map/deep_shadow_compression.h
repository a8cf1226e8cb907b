#pragma once
// Compression of a light ray's transmittance function (light_ray.h: per
// channel, continuous, piecewise linear, non-increasing) into at most N
// nodes (depth, r, g, b) shared by the three channels, the representation of
// a deep shadow map texel (Lokovic & Veach 2000, section 4.2).
//
// Error-bounded greedy (Lokovic & Veach): the raw function's breakpoints are
// fed front to back; from the last node the set of slopes whose line stays
// within +-tolerance of every point since that node is kept per channel (a
// cone); when a point empties a cone, a node is placed on the line at the
// previous point and the cone restarts there. The approximation between
// nodes is linear and within the tolerance at every breakpoint, hence
// everywhere (both functions are linear between breakpoints). Two savings
// that matter for few nodes:
//   - the first node (value 1) goes at the last point still within the
//     tolerance of 1, not at the entry into the volume;
//   - no closing node when everything after the last node is within the
//     tolerance of its value (the function stays constant after the last
//     node and before the first).
// So one opaque surface takes 2 nodes.
//
// A fixed N does not always meet a given tolerance. DeepShadowCompressor
// runs kDeepShadowLevels greedy compressions at once, with tolerances
// tolerance * 32^(k / 7) (k = 0..7: from 1x to 32x in steps of 1.64x), and
// keeps the smallest that fits in N nodes: the stored function is within
// that tolerance of the raw one. If none fits, the largest keeps its last
// node sliding to the end of the function (the error is then unbounded in
// its last piece, but the tail value is exact).
//
// The tail is made exact for the level kept: a raised tolerance let the
// value after the last node drift by up to 0.32, and that value is what
// every receiver behind the volume reads (a floor under a translucent shell
// around an opaque core got a grey shadow instead of a black one). When the
// kept nodes' tail differs from the function's last value by more than the
// base tolerance, a node with the exact value is added at the end (or the
// last node's value replaced when all N are used); the bound reported grows
// by that change. The levels are updated
// together, lane by lane in fixed-size arrays that the compiler vectorises;
// only node placements (rare) take a per-level branch.
#include "penumbra/base/lanes.h"
#include "penumbra/base/math.h"

namespace penumbra {

inline constexpr int kMaxDeepShadowNodes = 16;
inline constexpr int kDeepShadowLevels = 8;
inline constexpr float kDeepShadowLevelRatio = 1.6407f;  // 32^(1/7)

struct DeepShadowNode {
  float depth;
  vec3 transmittance;
};

// The nodes one level kept: within `tolerance` of the raw function unless
// `overflowed`.
struct DeepShadowNodes {
  const DeepShadowNode* nodes;
  int count;
  float tolerance;
  bool overflowed;
};

class DeepShadowCompressor {
 public:
  PENUMBRA_HD DeepShadowCompressor(float tolerance, int capacity) : capacity_(capacity) {
    float t = tolerance;
    for (int l = 0; l < kLevels; ++l) {
      tolerance_[l] = t;
      t *= kDeepShadowLevelRatio;
      state_[l] = kWaiting;
      count_[l] = 0;
      flat_[l] = 1;
      anchor_depth_[l] = -1e30f;  // keeps the shared update finite before a lane has a node
      for (int c = 0; c < 3; ++c) {
        anchor_value_[c][l] = 1.0f;
        slope_lo_[c][l] = -kInfinity;
        slope_hi_[c][l] = kInfinity;
      }
    }
  }

  // The next breakpoint (depth strictly increasing, values in [0, 1]; the
  // first one has value 1: the light enters the volume unattenuated).
  PENUMBRA_HD void add(float z, vec3 value) {
    // Every lane at once: narrow the cones; flag lanes whose cone empties.
    int attention = 0;
    for (int l = 0; l < kLevels; ++l) {
      const float inverse = 1.0f / (z - anchor_depth_[l]);
      const float tol = tolerance_[l];
      int fits = 1, near = 1;
      float lo[3], hi[3];
      for (int c = 0; c < 3; ++c) {
        const float delta = value[c] - anchor_value_[c][l];
        lo[c] = glm::max(slope_lo_[c][l], (delta - tol) * inverse);
        hi[c] = glm::min(slope_hi_[c][l], (delta + tol) * inverse);
        fits &= lo[c] <= hi[c];
        near &= glm::abs(delta) <= tol;
      }
      for (int c = 0; c < 3; ++c) {
        slope_lo_[c][l] = fits ? lo[c] : slope_lo_[c][l];
        slope_hi_[c][l] = fits ? hi[c] : slope_hi_[c][l];
      }
      flat_[l] &= near | (1 - fits);
      attention |= ((1 - fits) | (state_[l] != kActive)) << l;
    }
    // The few lanes that need a decision.
    for (int l = 0; attention != 0; ++l, attention >>= 1) {
      if (attention & 1) settle(l, z, value);
    }
    last_depth_ = z;
    last_value_ = value;
  }

  // Closes every level and returns the smallest tolerance that fits.
  PENUMBRA_HD DeepShadowNodes finish() {
    for (int l = 0; l < kLevels; ++l) {
      if (state_[l] != kActive || flat_[l]) continue;
      if (count_[l] == capacity_) {
        overflow(l, last_depth_, last_value_);
      } else {
        place_node(l);
      }
    }
    int chosen = kLevels - 1;
    for (int l = kLevels - 1; l >= 0; --l) {
      if (state_[l] != kOverflowed) chosen = l;
    }
    const bool overflowed = state_[chosen] == kOverflowed;
    const float tolerance = overflowed ? tolerance_[chosen] : tolerance_[chosen] + exact_tail(chosen);
    return DeepShadowNodes{nodes_[chosen], count_[chosen], tolerance, overflowed};
  }

 private:
  static constexpr int kLevels = kDeepShadowLevels;
  enum : int { kWaiting = 0, kActive = 1, kOverflowed = 2 };

  PENUMBRA_HD void settle(int l, float z, vec3 value) {
    if (state_[l] == kOverflowed) {
      if (l == kLevels - 1) nodes_[l][count_[l] - 1] = DeepShadowNode{z, value};  // slide to the end
      return;
    }
    if (state_[l] == kWaiting) {
      if (min_component(value) >= 1.0f - tolerance_[l]) {
        waiting_depth_[l] = z;  // still within the tolerance of 1: the first node moves along
        return;
      }
      // (The first breakpoint has value 1, so a waiting depth is set by now.)
      nodes_[l][0] = DeepShadowNode{waiting_depth_[l], vec3(1.0f)};
      count_[l] = 1;
      state_[l] = kActive;
      restart(l, z, value);
      return;
    }
    // Active, and the point emptied the cone: a node on the line at the previous point.
    if (count_[l] == capacity_) {
      overflow(l, z, value);
      return;
    }
    place_node(l);
    restart(l, z, value);
  }

  // A node at the last point on the line of the current cone's middle slope.
  // Not clamped to [0, 1]: that would move the line away from earlier
  // points; lookups clamp instead, which never increases the error.
  PENUMBRA_HD void place_node(int l) {
    const float dz = last_depth_ - anchor_depth_[l];
    vec3 v;
    for (int c = 0; c < 3; ++c) v[c] = anchor_value_[c][l] + 0.5f * (slope_lo_[c][l] + slope_hi_[c][l]) * dz;
    nodes_[l][count_[l]++] = DeepShadowNode{last_depth_, v};
  }

  // A new cone from the lane's last node through the point (z, value).
  PENUMBRA_HD void restart(int l, float z, vec3 value) {
    const DeepShadowNode& a = nodes_[l][count_[l] - 1];
    anchor_depth_[l] = a.depth;
    const float inverse = 1.0f / (z - a.depth);
    int near = 1;
    for (int c = 0; c < 3; ++c) {
      anchor_value_[c][l] = a.transmittance[c];
      const float delta = value[c] - a.transmittance[c];
      slope_lo_[c][l] = (delta - tolerance_[l]) * inverse;
      slope_hi_[c][l] = (delta + tolerance_[l]) * inverse;
      near &= glm::abs(delta) <= tolerance_[l];
    }
    flat_[l] = near;
  }

  // Makes the stored tail (the value after the last node) the raw function's
  // last value when they differ by more than the base tolerance, by adding a
  // node at the end or, with none left, moving the last node's value; returns
  // the change, which the error bound grows by (the approximation moves by at
  // most that much on the last piece and after it).
  PENUMBRA_HD float exact_tail(int l) {
    DeepShadowNode* nodes = nodes_[l];
    int& count = count_[l];
    const vec3 stored = count > 0 ? nodes[count - 1].transmittance : vec3(1.0f);
    const float change = max_component(glm::abs(last_value_ - stored));
    if (!(change > tolerance_[0])) return 0.0f;
    if (count == 0) {
      if (capacity_ < 2) return 0.0f;
      // Keep the function 1 in front of the attenuation (a lone node would make it constant).
      nodes[count++] = DeepShadowNode{waiting_depth_[l], vec3(1.0f)};
    }
    if (count < capacity_ && last_depth_ > nodes[count - 1].depth) {
      nodes[count++] = DeepShadowNode{last_depth_, last_value_};
    } else {
      nodes[count - 1].transmittance = last_value_;
    }
    return change;
  }

  PENUMBRA_HD void overflow(int l, float z, vec3 value) {
    state_[l] = kOverflowed;
    if (l == kLevels - 1) nodes_[l][count_[l] - 1] = DeepShadowNode{z, value};
  }

  int capacity_;
  float last_depth_ = -kInfinity;
  vec3 last_value_{1.0f};
  // Per level (lane l): tolerance, state, the cone from the last node.
  float tolerance_[kLevels];
  int state_[kLevels];
  int count_[kLevels];
  int flat_[kLevels];  // every point since the last node is within the tolerance of its value
  float waiting_depth_[kLevels] = {-kInfinity, -kInfinity, -kInfinity, -kInfinity,
                                   -kInfinity, -kInfinity, -kInfinity, -kInfinity};
  float anchor_depth_[kLevels];
  float anchor_value_[3][kLevels];
  float slope_lo_[3][kLevels];
  float slope_hi_[3][kLevels];
  DeepShadowNode nodes_[kLevels][kMaxDeepShadowNodes];
};

// Evaluates nodes (depth ascending; unused ones at +inf depth) at depth z:
// constant before the first and after the last, linear between, clamped to
// [0, 1] (node values may lie slightly outside it, see add()).
template <class L>
PENUMBRA_HD PENUMBRA_FORCE_INLINE typename L::Vec3 evaluate_deep_shadow(const float* texels, typename L::Index texel,
                                                                        int node_count, typename L::Float z) {
  // texels + texel: node_count * (depth, r, g, b), per lane
  using F = typename L::Float;
  using V = typename L::Vec3;
  using X = typename L::Index;
  const auto node = [&](int k, int c) { return gather(texels, texel + X(4 * k + c)); };
  F depth = node(0, 0);
  V value(node(0, 1), node(0, 2), node(0, 3));
  auto open = z > depth;  // lanes still looking for the node after z
  for (int k = 1; k < node_count && any(open); ++k) {
    const F next = node(k, 0);
    const V next_value(node(k, 1), node(k, 2), node(k, 3));
    const auto between = open & (z < next);
    const F f = (z - depth) / (next - depth);  // 0 toward an unused node at +inf
    value = select(between, value + f * (next_value - value), value);
    open = open & !between;
    depth = select(open, next, depth);
    value = select(open, next_value, value);
  }
  return clamp(value, V(0.0f), V(1.0f));
}

PENUMBRA_HD inline vec3 evaluate_deep_shadow(const float* texel, int node_count, float z) {
  return evaluate_deep_shadow<ScalarLanes>(texel, 0, node_count, z);
}

}  // namespace penumbra

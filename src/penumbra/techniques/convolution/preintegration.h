#pragma once
// Pre-integrated transfer function for the slab renderer's few-slab case
// (Patel et al. 2013, Fig. 19), after Engel, Kraus and Ertl 2001,
// "High-quality pre-integrated volume rendering using hardware-accelerated
// pixel shading". A segment of world length L whose scalar runs linearly from
// s_f (front) to s_b (back) has, with sigma(s) and c(s) from the TF,
//   alpha(s_f, s_b)  = 1 - exp(-L * int_0^1 sigma(s(t)) dt)
//   colour(s_f, s_b) = int_0^L c sigma exp(-int_0^x sigma) dx / alpha
// i.e. the mean scattering colour seen from the front, so that a lit segment
// adds alpha * colour * lighting and its shadow transmittance is 1 - alpha.
// A thin feature of the TF between s_f and s_b is integrated, not missed as
// it is by point samples at the segment's ends.
//
// Building: the table spans the TF's value range with N values s_0..s_{N-1}.
// The optical depth is exact from the integral function S(s) = int sigma ds of
// the piecewise-linear TF: tau = L (S(s_b) - S(s_f)) / (s_b - s_f). The colour
// composites the segment front to back as its |j - i| sub-segments between
// neighbouring table values, each with its exact opacity and its
// sigma-weighted mean colour (int c sigma ds / int sigma ds, also exact from an
// integral function); that is exact when the colour is constant over a
// sub-segment and otherwise correct to the table's resolution. Per difference
// d = |j - i| the sub-segment opacities are shared by all its entries, so
// the build takes N^2 exponentials and ~N^3/3 multiply-adds (~10 ms at N = 256
// on one core), run over d in parallel.
#include "penumbra/base/math.h"
#include "penumbra/scene/transfer_function.h"

#include <cstdint>
#include <vector>

namespace penumbra {

// Entries (rgb colour, alpha) at entries[i_front * size + i_back], the table
// values being value_min + i / index_scale. Bilinear lookup interpolates the
// opacity-weighted colour (so a transparent neighbour does not tint it).
struct PreintegrationView {
  const vec4* entries = nullptr;
  int size = 0;
  float value_min = 0.0f;
  float index_scale = 0.0f;  // (size - 1) / (value_max - value_min)

  // (colour rgb, alpha) of the segment from s_front to s_back; values outside
  // the range take the end entries, NaN and +-inf are transparent.
  PENUMBRA_HD vec4 lookup(float s_front, float s_back) const {
    if (!is_finite(s_front) || !is_finite(s_back)) return vec4(0.0f);
    const float last = float(size - 1);
    const float x = glm::clamp((s_front - value_min) * index_scale, 0.0f, last);
    const float y = glm::clamp((s_back - value_min) * index_scale, 0.0f, last);
    const int i = glm::min(int(x), size - 2);
    const int j = glm::min(int(y), size - 2);
    const float fx = x - float(i), fy = y - float(j);
    const vec4* row0 = entries + std::int64_t(i) * size + j;
    const vec4* row1 = row0 + size;
    const float w[4] = {(1.0f - fx) * (1.0f - fy), (1.0f - fx) * fy, fx * (1.0f - fy), fx * fy};
    const vec4 e[4] = {row0[0], row0[1], row1[0], row1[1]};
    vec3 weighted(0.0f), plain(0.0f);
    float alpha = 0.0f;
    for (int k = 0; k < 4; ++k) {
      weighted += (w[k] * e[k].a) * vec3(e[k]);
      plain += w[k] * vec3(e[k]);
      alpha += w[k] * e[k].a;
    }
    return vec4(alpha > 0.0f ? weighted / alpha : plain, alpha);
  }
};

class PreintegrationTable {
 public:
  static constexpr int kDefaultSize = 256;
  static constexpr int kMaxSize = 2048;  // the build is O(size^3)

  PreintegrationTable() = default;
  // Over the TF view's value range, for segments of world length `length`.
  // Throws InvalidArgument("size") for size outside [2, kMaxSize],
  // InvalidArgument("length") for a length that is not positive and finite,
  // InvalidArgument("transfer_function") for an empty TF view or one with no
  // value range; OutOfMemoryBudget when the table does not fit.
  PreintegrationTable(const TransferFunctionView& tf, float length, int size = kDefaultSize);

  PreintegrationView view() const;
  bool empty() const { return entries_.empty(); }
  int size() const { return size_; }
  float length() const { return length_; }
  std::uint64_t bytes() const { return entries_.size() * sizeof(vec4); }

 private:
  std::vector<vec4> entries_;
  int size_ = 0;
  float length_ = 0.0f;
  float value_min_ = 0.0f;
  float index_scale_ = 0.0f;
};

// Keeps one table and rebuilds it only when the TF's entries or range, the
// segment length or the size change (the TF's entries are compared by value,
// so a table edited in place is noticed).
class PreintegrationCache {
 public:
  // Returns true when the table was rebuilt. Throws as PreintegrationTable.
  bool update(const TransferFunctionView& tf, float length, int size = PreintegrationTable::kDefaultSize);

  const PreintegrationTable& table() const { return table_; }
  PreintegrationView view() const { return table_.view(); }
  std::uint64_t bytes() const { return table_.bytes() + tf_entries_.size() * sizeof(vec4); }

 private:
  PreintegrationTable table_;
  std::vector<vec4> tf_entries_;  // the TF the table was built from
  float tf_value_min_ = 0.0f;
  float tf_index_scale_ = 0.0f;
};

}  // namespace penumbra

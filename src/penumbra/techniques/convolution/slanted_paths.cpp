#include "penumbra/techniques/convolution/slanted_paths.h"

#include "penumbra/base/parallel.h"
#include "penumbra/techniques/convolution/mesh_layers.h"

namespace penumbra {

void SurfaceRuns::from_ldi(const LdiView& ldi, int width, int height, int shift, int version) {
  if (version == version_ && shift == shift_ && width == width_ && height == height_) {
    start_cursors();
    return;
  }
  width_ = width;
  height_ = height;
  shift_ = shift;
  version_ = version;
  const std::size_t pixels = std::size_t(width) * std::size_t(height);
  offsets_.assign(pixels + 1, 0u);
  runs_.clear();
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const PixelLayers layers = start_layers(ldi, x + shift, y + shift);
      std::uint32_t inside = layers.inside;
      float begin = -kInfinity;
      for (std::uint32_t f = layers.next; f < layers.end; ++f) {
        const LdiFragment& fragment = ldi.fragments[f];
        const std::uint32_t was = inside;
        inside ^= 1u << fragment.object;
        if (was == 0u && inside != 0u) begin = fragment.depth;
        if (was != 0u && inside == 0u) runs_.push_back(vec2(begin, fragment.depth));
      }
      if (inside != 0u) runs_.push_back(vec2(begin, kInfinity));
      offsets_[std::size_t(x) + std::size_t(width) * std::size_t(y) + 1] = std::uint32_t(runs_.size());
    }
  }
  start_cursors();
}

void SurfaceRuns::from_intervals(const std::vector<vec2>& runs, int width, int height) {
  width_ = width;
  height_ = height;
  shift_ = version_ = -1;
  const std::size_t pixels = std::size_t(width) * std::size_t(height);
  offsets_.assign(pixels + 1, 0u);
  runs_.clear();
  for (std::size_t i = 0; i < pixels; ++i) {
    if (runs[i].x <= runs[i].y) runs_.push_back(runs[i]);
    offsets_[i + 1] = std::uint32_t(runs_.size());
  }
  start_cursors();
}

// Once the runs are in: every pixel before its first run, none current.
void SurfaceRuns::start_cursors() {
  const std::size_t pixels = offsets_.size() - 1;
  cursor_.assign(offsets_.begin(), offsets_.end() - 1);
  current_.assign(pixels, vec2(1.0f, 0.0f));
  gradients_.assign(pixels, vec4(0.0f));
  with_runs_.clear();
  for (std::size_t i = 0; i < pixels; ++i) {
    if (offsets_[i + 1] > offsets_[i]) with_runs_.push_back(std::uint32_t(i));
  }
}

void SurfaceRuns::enter_slab(float z0, float e) {
  const float z1 = z0 + e, reach = 4.0f * e;
  const auto gap = [&](vec2 r) { return r.x > z1 ? r.x - z1 : (r.y < z0 ? z0 - r.y : 0.0f); };
  const std::int64_t count = std::int64_t(with_runs_.size());
  parallel_for(0, count, [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t j = first; j < last; ++j) {
      const std::size_t i = with_runs_[std::size_t(j)];
      const std::uint32_t end = offsets_[i + 1];
      std::uint32_t& c = cursor_[i];
      while (c + 1 < end && gap(runs_[c + 1]) <= gap(runs_[c])) ++c;
      const vec2 r = runs_[c];
      current_[i] = vec2(glm::max(r.x, z0 - reach), glm::min(r.y, z1 + reach));
    }
  }, 256);
  // Central differences where both neighbours' rays have a run, else one-sided.
  parallel_for(0, count, [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t j = first; j < last; ++j) {
      const std::size_t i = with_runs_[std::size_t(j)];
      const int x = int(i % std::size_t(width_)), y = int(i / std::size_t(width_));
      const vec2 r = current_[i];
      vec2 grad_h(0.0f), grad_g(0.0f);
      for (int a = 0; a < 2; ++a) {
        const std::size_t step = a == 0 ? 1 : std::size_t(width_);
        const bool has_lo = a == 0 ? x > 0 : y > 0, has_hi = a == 0 ? x + 1 < width_ : y + 1 < height_;
        const vec2 lo = has_lo ? current_[i - step] : vec2(1.0f, 0.0f);
        const vec2 hi = has_hi ? current_[i + step] : vec2(1.0f, 0.0f);
        const bool lo_run = lo.x <= lo.y, hi_run = hi.x <= hi.y;
        if (lo_run && hi_run) {
          grad_h[a] = 0.5f * (hi.x - lo.x);
          grad_g[a] = 0.5f * (hi.y - lo.y);
        } else if (hi_run) {
          grad_h[a] = hi.x - r.x;
          grad_g[a] = hi.y - r.y;
        } else if (lo_run) {
          grad_h[a] = r.x - lo.x;
          grad_g[a] = r.y - lo.y;
        }
      }
      gradients_[i] = vec4(grad_h, grad_g);
    }
  }, 256);
}

void SlantedPaths::start(const LdiView* ldi, int shift, int ldi_version, const std::vector<vec2>& box, int width,
                         int height) {
  width_ = width;
  height_ = height;
  meshes_on_ = ldi != nullptr;
  if (meshes_on_) meshes_.from_ldi(*ldi, width, height, shift, ldi_version);
  box_.from_intervals(box, width, height);
  const std::size_t pixels = std::size_t(width) * std::size_t(height);
  // The pixels with a run of either kind, in order.
  active_.clear();
  const std::vector<std::uint32_t>& a = box_.pixels_with_runs();
  static const std::vector<std::uint32_t> none;
  const std::vector<std::uint32_t>& b = meshes_on_ ? meshes_.pixels_with_runs() : none;
  std::size_t ia = 0, ib = 0;
  while (ia < a.size() || ib < b.size()) {
    if (ib == b.size() || (ia < a.size() && a[ia] < b[ib])) {
      active_.push_back(a[ia++]);
    } else {
      if (ia < a.size() && a[ia] == b[ib]) ++ia;
      active_.push_back(b[ib++]);
    }
  }
  live_.assign(pixels, 0);
  covered_.assign(pixels, 0);
  mesh_sigma_.assign(pixels, vec3(0.0f));
  volume_sigma_.assign(pixels, 0.0f);
}

void SlantedPaths::enter_slab(const SlabFrame& frame, float z, const std::vector<vec2>& light_means) {
  e_ = frame.slab_distance;
  z0_ = z - 0.5f * e_;
  if (meshes_on_) meshes_.enter_slab(z0_, e_);
  box_.enter_slab(z0_, e_);
  map_ = slab_mapping(frame, z);
  drift_offset_.resize(light_means.size());
  for (std::size_t l = 0; l < light_means.size(); ++l) {
    // The light reaching pixel P came from P + w on the slab before (w =
    // pixels_per_unit (-mean.x, mean.y)): it travels -w.
    drift_offset_[l] = -map_.pixels_per_unit * vec2(-light_means[l].x, light_means[l].y);
  }
}

void SlantedPaths::attenuate(float* const* planes, int light_count, int channels, const std::vector<float>& light_path,
                             std::uint8_t* has_medium) const {
  const float z = z0_ + 0.5f * e_, z1 = z0_ + e_;
  parallel_for(0, std::int64_t(active_.size()), [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t j = first; j < last; ++j) {
      {
        const std::size_t i = active_[std::size_t(j)];
        const int x = int(i % std::size_t(width_)), y = int(i / std::size_t(width_));
        if (!live_[i]) continue;
        // Where only the path meets a medium, its neighbours' extinction.
        const bool mesh_run = meshes_on_ && meshes_.any(i), box_run = box_.any(i);
        vec3 mesh_sigma = mesh_sigma_[i];
        float volume_sigma = volume_sigma_[i];
        const std::size_t row = std::size_t(width_);
        const bool lo_x = x > 0, hi_x = x + 1 < width_, lo_y = y > 0, hi_y = y + 1 < height_;
        if (mesh_run && !(covered_[i] & 1)) {
          if (lo_x) mesh_sigma = glm::max(mesh_sigma, mesh_sigma_[i - 1]);
          if (hi_x) mesh_sigma = glm::max(mesh_sigma, mesh_sigma_[i + 1]);
          if (lo_y) mesh_sigma = glm::max(mesh_sigma, mesh_sigma_[i - row]);
          if (hi_y) mesh_sigma = glm::max(mesh_sigma, mesh_sigma_[i + row]);
        }
        if (box_run && !(covered_[i] & 2)) {
          if (lo_x) volume_sigma = glm::max(volume_sigma, volume_sigma_[i - 1]);
          if (hi_x) volume_sigma = glm::max(volume_sigma, volume_sigma_[i + 1]);
          if (lo_y) volume_sigma = glm::max(volume_sigma, volume_sigma_[i - row]);
          if (hi_y) volume_sigma = glm::max(volume_sigma, volume_sigma_[i + row]);
        }
        const bool mesh = mesh_run && max_component(mesh_sigma) > 0.0f;
        const bool volume = box_run && volume_sigma > 0.0f;
        if (!mesh && !volume) continue;
        bool met = false;
        for (int l = 0; l < light_count; ++l) {
          vec3 depth(0.0f);
          if (mesh) {
            const float length = inside_mesh(l, x, int(y), z, z1);
            met = met || length > 0.0f;
            depth += mesh_sigma * (length / e_);
          }
          if (volume) {
            const float length = inside_box(l, x, int(y), z, z1);
            met = met || length > 0.0f;
            depth += vec3(volume_sigma * (length / e_));
          }
          depth *= light_path[std::size_t(l)];
          for (int c = 0; c < channels; ++c) planes[l * channels + c][i] *= exp_nonpositive(-depth[c]);
        }
        if (met && has_medium) has_medium[i] = 1;
      }
    }
  }, 256);
}

}  // namespace penumbra

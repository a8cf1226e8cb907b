#include "penumbra/volume/volume.h"

#include "penumbra/base/error.h"
#include "penumbra/base/memory_budget.h"
#include "penumbra/base/parallel.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

namespace penumbra {

void Volume::check_dims(ivec3 dims, int frame_count) const {
  if (dims.x <= 0 || dims.y <= 0 || dims.z <= 0) {
    throw InvalidArgument("dims", fmt::format("volume dimensions must be positive, got {}x{}x{}", dims.x,
                                              dims.y, dims.z));
  }
  if (frame_count <= 0) throw InvalidArgument("frames", "a volume needs at least one frame");
}

Volume::Volume(ivec3 dims, VoxelType type, int frame_count) : dims_(dims), type_(type) {
  check_dims(dims, frame_count);
  const std::uint64_t bytes = checked_product(
      {std::uint64_t(dims.x), std::uint64_t(dims.y), std::uint64_t(dims.z), voxel_size(type),
       std::uint64_t(frame_count)});
  check_memory_budget(fmt::format("a {}x{}x{} {} volume with {} frame(s)", dims.x, dims.y, dims.z,
                                  to_string(type), frame_count),
                      bytes);
  owned_.reserve(static_cast<std::size_t>(frame_count));
  for (int f = 0; f < frame_count; ++f) {
    owned_.emplace_back(new std::byte[frame_bytes()]);
    frames_.push_back(owned_.back().get());
  }
  center_at_origin();
}

Volume Volume::wrap(ivec3 dims, VoxelType type, int frame_count, const std::byte* data,
                    std::shared_ptr<const void> owner) {
  Volume v;
  v.check_dims(dims, frame_count);
  if (data == nullptr) throw InvalidArgument("data", "a wrapped volume needs its voxels");
  v.dims_ = dims;
  v.type_ = type;
  // The engine reads wrapped memory only through const views; the pointer is
  // stored without const so owned and wrapped frames share one table.
  std::byte* first = const_cast<std::byte*>(data);
  for (int f = 0; f < frame_count; ++f) v.frames_.push_back(first + std::uint64_t(f) * v.frame_bytes());
  v.external_owner_ = owner ? std::move(owner) : std::make_shared<int>(0);
  v.center_at_origin();
  return v;
}

Volume::Volume(Volume&& other) noexcept { *this = std::move(other); }

Volume& Volume::operator=(Volume&& other) noexcept {
  if (this != &other) {
    std::scoped_lock lock(range_mutex_, other.range_mutex_);
    dims_ = other.dims_;
    type_ = other.type_;
    spacing_ = other.spacing_;
    origin_ = other.origin_;
    frames_ = std::move(other.frames_);
    owned_ = std::move(other.owned_);
    external_owner_ = std::move(other.external_owner_);
    source_ = std::move(other.source_);
    ranges_stale_ = other.ranges_stale_;
    ranges_ = std::move(other.ranges_);
  }
  return *this;
}

Volume::~Volume() = default;

std::uint64_t Volume::voxel_count() const {
  return std::uint64_t(dims_.x) * std::uint64_t(dims_.y) * std::uint64_t(dims_.z);
}

std::uint64_t Volume::frame_bytes() const { return voxel_count() * voxel_size(type_); }

namespace {

// Every corner of a volume's world box lies within +-kMaxWorldCoordinate, so
// that box extents and their lengths (which square them) stay finite in float:
// a spacing of 1e38 would put the centred box at infinity.
constexpr double kMaxWorldCoordinate = 1e18;

void check_box(ivec3 dims, vec3 origin, vec3 spacing, const char* name) {
  for (int a = 0; a < 3; ++a) {
    const double far = std::abs(double(origin[a])) + double(dims[a] - 1) * double(spacing[a]);
    if (!(far <= kMaxWorldCoordinate)) {
      throw InvalidArgument(name, fmt::format("the volume's box reaches {:.3g} along axis {}, beyond the {:.0e} a "
                                              "world coordinate may have (spacing {} over {} voxels, origin {})",
                                              far, a + 1, kMaxWorldCoordinate, spacing[a], dims[a], origin[a]));
    }
  }
}

}  // namespace

void Volume::set_spacing(vec3 spacing) {
  if (!(spacing.x > 0.0f && spacing.y > 0.0f && spacing.z > 0.0f) || !is_finite(spacing.x) ||
      !is_finite(spacing.y) || !is_finite(spacing.z)) {
    throw InvalidArgument("spacing", fmt::format("voxel spacing must be positive and finite, got {} {} {}",
                                                 spacing.x, spacing.y, spacing.z));
  }
  const bool centred = origin_ == -0.5f * vec3(dims_ - 1) * spacing_;
  const vec3 origin = centred ? -0.5f * vec3(dims_ - 1) * spacing : origin_;
  check_box(dims_, origin, spacing, "spacing");
  spacing_ = spacing;
  origin_ = origin;
}

void Volume::set_origin(vec3 origin) {
  if (!is_finite(origin.x) || !is_finite(origin.y) || !is_finite(origin.z)) {
    throw InvalidArgument("origin", "volume origin must be finite");
  }
  check_box(dims_, origin, spacing_, "origin");
  origin_ = origin;
}


void Volume::center_at_origin() { origin_ = -0.5f * vec3(dims_ - 1) * spacing_; }

Box3 Volume::world_box() const { return Box3{origin_, origin_ + vec3(dims_ - 1) * spacing_}; }

void Volume::check_frame(int frame) const {
  if (frame < 0 || frame >= frame_count()) {
    throw InvalidArgument("time_step",
                          fmt::format("frame {} does not exist; the volume has {} frame(s)", frame, frame_count()));
  }
}

void Volume::check_type(VoxelType requested) const {
  if (requested != type_) {
    throw InvalidArgument("voxel type", fmt::format("volume stores {}, not {}", to_string(type_),
                                                    to_string(requested)));
  }
}

std::byte* Volume::frame_data(int frame) {
  check_frame(frame);
  if (wraps_external_memory()) {
    throw InvalidArgument("volume", "the voxels of a wrapped volume are written by their owner, not through the volume");
  }
  std::lock_guard lock(range_mutex_);
  ranges_stale_ = true;
  return frames_[static_cast<std::size_t>(frame)];
}

const std::byte* Volume::frame_data(int frame) const {
  check_frame(frame);
  return frames_[static_cast<std::size_t>(frame)];
}

void Volume::mark_modified() {
  std::lock_guard lock(range_mutex_);
  ranges_stale_ = true;
}

namespace {

template <class T> ValueRange compute_range(const T* data, std::uint64_t count) {
  struct Partial {
    float min = std::numeric_limits<float>::infinity();
    float max = -std::numeric_limits<float>::infinity();
    std::uint64_t non_finite = 0;
  };
  constexpr std::int64_t kChunk = 1 << 20;
  const std::int64_t chunks = static_cast<std::int64_t>((count + kChunk - 1) / kChunk);
  std::vector<Partial> partial(static_cast<std::size_t>(chunks));
  parallel_for(0, chunks, [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t c = first; c < last; ++c) {
      Partial p;
      const std::uint64_t end = std::min<std::uint64_t>(count, std::uint64_t(c + 1) * kChunk);
      const std::uint64_t begin = std::uint64_t(c) * kChunk;
      if constexpr (std::is_floating_point_v<T>) {
        for (std::uint64_t i = begin; i < end; ++i) {
          const float v = static_cast<float>(data[i]);
          if (!is_finite(v)) {
            ++p.non_finite;
            continue;
          }
          p.min = std::min(p.min, v);
          p.max = std::max(p.max, v);
        }
      } else {
        T lo = data[begin], hi = data[begin];
        for (std::uint64_t i = begin + 1; i < end; ++i) {
          lo = std::min(lo, data[i]);
          hi = std::max(hi, data[i]);
        }
        p.min = static_cast<float>(lo);
        p.max = static_cast<float>(hi);
      }
      partial[static_cast<std::size_t>(c)] = p;
    }
  });
  Partial total;
  for (const Partial& p : partial) {
    total.min = std::min(total.min, p.min);
    total.max = std::max(total.max, p.max);
    total.non_finite += p.non_finite;
  }
  if (total.min > total.max) return ValueRange{0.0f, 0.0f, total.non_finite};  // all non-finite
  return ValueRange{total.min, total.max, total.non_finite};
}

}  // namespace

void Volume::update_ranges() const {
  // Caller holds range_mutex_.
  if (!ranges_stale_) return;
  ranges_.clear();
  for (int f = 0; f < frame_count(); ++f) {
    const std::byte* bytes = frames_[static_cast<std::size_t>(f)];
    ranges_.push_back(visit_voxel_type(type_, [&](auto tag) {
      using T = decltype(tag);
      return compute_range(reinterpret_cast<const T*>(bytes), voxel_count());
    }));
  }
  ranges_stale_ = false;
}

ValueRange Volume::value_range(int frame) const {
  check_frame(frame);
  std::lock_guard lock(range_mutex_);
  update_ranges();
  return ranges_[static_cast<std::size_t>(frame)];
}

ValueRange Volume::value_range() const {
  std::lock_guard lock(range_mutex_);
  update_ranges();
  ValueRange total = ranges_.front();
  for (const ValueRange& r : ranges_) {
    total.min = std::min(total.min, r.min);
    total.max = std::max(total.max, r.max);
  }
  total.non_finite = 0;
  for (const ValueRange& r : ranges_) total.non_finite += r.non_finite;
  return total;
}

float Volume::voxel(int frame, ivec3 index) const {
  if (glm::any(glm::lessThan(index, ivec3(0))) || glm::any(glm::greaterThanEqual(index, dims_))) {
    throw InvalidArgument("index", fmt::format("voxel ({}, {}, {}) is outside the {}x{}x{} grid", index.x,
                                               index.y, index.z, dims_.x, dims_.y, dims_.z));
  }
  return view(frame).voxel(index);
}

VolumeView Volume::view(int frame) const {
  check_frame(frame);
  VolumeView v;
  v.data = frames_[static_cast<std::size_t>(frame)];
  v.type = type_;
  v.dims = dims_;
  v.spacing = spacing_;
  v.origin = origin_;
  return v;
}

}  // namespace penumbra

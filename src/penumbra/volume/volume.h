#pragma once
// Volume: a grid of scalars of one voxel type, with spacing, origin and one or
// more time steps (frames) that share the grid. It owns its voxels, or wraps
// memory that lives elsewhere (a numpy array) and keeps that memory's owner
// alive; either way the voxels of a frame are contiguous, x fastest.
#include "penumbra/base/math.h"
#include "penumbra/base/ray.h"
#include "penumbra/volume/volume_view.h"
#include "penumbra/volume/voxel_type.h"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace penumbra {

struct ValueRange {
  float min = 0.0f;
  float max = 0.0f;
  // Voxels that are NaN or +-inf; they are left out of min/max and sample as
  // transparent (see TransferFunctionView::lookup).
  std::uint64_t non_finite = 0;
};

class Volume {
 public:
  // Allocates dims.x * dims.y * dims.z voxels per frame after checking the
  // memory budget; the voxels are uninitialised. Throws InvalidArgument for
  // non-positive dims, spacing or frame count and OutOfMemoryBudget when too big.
  Volume(ivec3 dims, VoxelType type, int frame_count = 1);

  // Wraps `frame_count` frames of voxels that start at `data` (frame f at
  // data + f * frame_bytes()) without copying them. `owner` keeps that memory
  // alive for as long as the volume exists. The memory is read-only through
  // the volume: the non-const frame_data() throws. There is no room after the
  // last voxel for padding (a reader of whole SIMD packets past the end must
  // not be given a wrapped volume's memory). Throws InvalidArgument for
  // non-positive dims or frame count or a null `data`.
  static Volume wrap(ivec3 dims, VoxelType type, int frame_count, const std::byte* data,
                     std::shared_ptr<const void> owner);

  Volume(const Volume&) = delete;
  Volume& operator=(const Volume&) = delete;
  Volume(Volume&&) noexcept;
  Volume& operator=(Volume&&) noexcept;
  ~Volume();

  ivec3 dims() const { return dims_; }
  VoxelType type() const { return type_; }
  int frame_count() const { return static_cast<int>(frames_.size()); }
  std::uint64_t voxel_count() const;
  std::uint64_t frame_bytes() const;
  std::uint64_t total_bytes() const { return frame_bytes() * frames_.size(); }

  vec3 spacing() const { return spacing_; }
  void set_spacing(vec3 spacing);
  // World position of voxel (0,0,0). Until set, the grid is centred at the
  // world origin.
  vec3 origin() const { return origin_; }
  void set_origin(vec3 origin);
  void center_at_origin();
  Box3 world_box() const;

  // Raw voxel bytes of one frame (x fastest, then y, then z). Writing through
  // the non-const overload marks the value ranges stale; it throws
  // InvalidArgument for a wrapped volume.
  std::byte* frame_data(int frame);
  const std::byte* frame_data(int frame) const;

  template <class T> T* frame_as(int frame) {
    check_type(VoxelTypeOf<T>::value);
    return reinterpret_cast<T*>(frame_data(frame));
  }
  template <class T> const T* frame_as(int frame) const {
    check_type(VoxelTypeOf<T>::value);
    return reinterpret_cast<const T*>(frame_data(frame));
  }

  // Value range of one frame and of all frames together (NaN/inf excluded).
  ValueRange value_range(int frame) const;
  ValueRange value_range() const;

  // Whether the voxels live in memory the volume does not own (wrap()).
  bool wraps_external_memory() const { return external_owner_ != nullptr; }
  // After the wrapped memory was written by its owner: forgets the cached
  // value ranges. (Scenes and techniques see new voxels only once the volume
  // is set on the scene again, which moves the data version.)
  void mark_modified();

  // Voxel values of one frame as float, for analysis and tests.
  float voxel(int frame, ivec3 index) const;

  VolumeView view(int frame = 0) const;

  // A free-form note on where the volume came from (file path, generator).
  const std::string& source() const { return source_; }
  void set_source(std::string source) { source_ = std::move(source); }

 private:
  Volume() = default;
  void check_dims(ivec3 dims, int frame_count) const;
  void check_frame(int frame) const;
  void check_type(VoxelType requested) const;
  void update_ranges() const;

  ivec3 dims_{0};
  VoxelType type_ = VoxelType::UInt8;
  vec3 spacing_{1.0f};
  vec3 origin_{0.0f};
  std::vector<std::byte*> frames_;                   // where each frame starts
  std::vector<std::unique_ptr<std::byte[]>> owned_;  // the frames, when the volume owns them
  std::shared_ptr<const void> external_owner_;       // keeps wrapped memory alive
  std::string source_;

  mutable std::mutex range_mutex_;
  mutable bool ranges_stale_ = true;
  mutable std::vector<ValueRange> ranges_;
};

}  // namespace penumbra

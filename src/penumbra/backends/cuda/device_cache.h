#pragma once
// DeviceCache: the CUDA backend's device memory for one owner (a technique's
// SceneResources, through RenderView::device_state). Host arrays are
// mirrored once per version: persistent() uploads an array only when it is
// new or its size or version changed, so a frame uploads nothing but its
// small per-frame structs (frame()) unless the scene changed. Every
// allocation is checked first against the device memory budget
// (device_memory_budget_bytes()) and the memory the device has free, with an
// OutOfMemoryBudget error naming what needed it.
//
// Host code only. The memory operations are a DeviceMemory: the CUDA
// runtime's (cuda_memory(), in builds with CUDA) or plain host memory
// (host_memory(), which the CPU tests use to check what is uploaded when).
#include <cstddef>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

namespace penumbra {

class DeviceMemory {
 public:
  virtual ~DeviceMemory() = default;
  // Throws OutOfMemoryBudget when the device has not `bytes` free.
  virtual void* allocate(std::size_t bytes, const char* what) const = 0;
  virtual void release(void* device) const = 0;
  virtual void upload(void* device, const void* host, std::size_t bytes) const = 0;
  virtual void zero(void* device, std::size_t bytes) const = 0;
};

const DeviceMemory& host_memory();
const DeviceMemory& cuda_memory();  // defined only in builds with CUDA

// Uploads of persistent mirrors by every DeviceCache of the process.
std::uint64_t device_uploads();

class DeviceCache {
 public:
  explicit DeviceCache(const DeviceMemory& memory) : memory_(memory) {}
  DeviceCache(const DeviceCache&) = delete;
  DeviceCache& operator=(const DeviceCache&) = delete;
  ~DeviceCache();

  // Starts a frame: frees the previous frame's per-frame copies and marks
  // every persistent mirror unused.
  void begin_frame();
  // Ends a frame: frees the persistent mirrors the frame did not use (the
  // structures of a technique state that no longer exists).
  void end_frame();

  // The device copy of host[0, bytes) as of `version` (nullptr for none).
  // The same array asked for under another version or size replaces its
  // mirror; one already handed out in this frame lives to the frame's end.
  void* persistent(const void* host, std::size_t bytes, std::uint64_t version, const char* what);
  // A device copy valid until the next begin_frame().
  void* frame(const void* host, std::size_t bytes, const char* what);
  // Zeroed device memory valid until the next begin_frame().
  void* frame_zeroed(std::size_t bytes, const char* what);
  // Device memory of at least `bytes` kept from frame to frame (the output
  // image), contents undefined.
  void* scratch(std::size_t bytes, const char* what);

  // Device memory held now, and the mirrors uploaded so far (tests check
  // that an unchanged scene uploads nothing).
  std::uint64_t bytes() const { return bytes_; }
  std::uint64_t uploads() const { return uploads_; }

 private:
  struct Mirror {
    void* device = nullptr;
    std::size_t bytes = 0;
    std::uint64_t version = 0;
    bool used = false;
  };
  void* allocate(std::size_t bytes, const char* what);
  void release(void* device, std::size_t bytes);

  const DeviceMemory& memory_;
  std::unordered_map<const void*, Mirror> mirrors_;
  std::vector<std::pair<void*, std::size_t>> frame_;
  void* scratch_ = nullptr;
  std::size_t scratch_bytes_ = 0;
  std::uint64_t bytes_ = 0;
  std::uint64_t uploads_ = 0;
};

// Throws Error("cuda: <call>: <message>") when `status` (a cudaError_t) is
// not success (cuda_runtime.cpp).
void check_cuda(int status, const char* call);

}  // namespace penumbra

#include "penumbra/backends/cuda/device_cache.h"

#include "penumbra/backends/device.h"
#include "penumbra/base/error.h"

#include <atomic>
#include <cstdlib>
#include <cstring>
#include <string>

namespace penumbra {
namespace {

std::atomic<std::uint64_t> g_uploads{0};

class HostMemory final : public DeviceMemory {
 public:
  void* allocate(std::size_t bytes, const char* what) const override {
    void* p = std::malloc(bytes);
    if (!p) throw OutOfMemoryBudget(std::string("host memory for ") + what, bytes, 0);
    return p;
  }
  void release(void* device) const override { std::free(device); }
  void upload(void* device, const void* host, std::size_t bytes) const override { std::memcpy(device, host, bytes); }
  void zero(void* device, std::size_t bytes) const override { std::memset(device, 0, bytes); }
};

}  // namespace

const DeviceMemory& host_memory() {
  static const HostMemory memory;
  return memory;
}

std::uint64_t device_uploads() { return g_uploads.load(); }

DeviceCache::~DeviceCache() {
  for (auto& [device, bytes] : frame_) memory_.release(device);
  for (auto& [host, mirror] : mirrors_) memory_.release(mirror.device);
  if (scratch_) memory_.release(scratch_);
}

void* DeviceCache::allocate(std::size_t bytes, const char* what) {
  const std::uint64_t budget = device_memory_budget_bytes();
  if (budget != 0 && bytes_ + bytes > budget) {
    throw OutOfMemoryBudget(std::string("device memory for ") + what, bytes_ + bytes, budget);
  }
  void* device = memory_.allocate(bytes, what);
  bytes_ += bytes;
  return device;
}

void DeviceCache::release(void* device, std::size_t bytes) {
  memory_.release(device);
  bytes_ -= bytes;
}

void DeviceCache::begin_frame() {
  for (auto& [device, bytes] : frame_) release(device, bytes);
  frame_.clear();
  for (auto& [host, mirror] : mirrors_) mirror.used = false;
}

void DeviceCache::end_frame() {
  for (auto it = mirrors_.begin(); it != mirrors_.end();) {
    if (it->second.used) {
      ++it;
      continue;
    }
    release(it->second.device, it->second.bytes);
    it = mirrors_.erase(it);
  }
}

void* DeviceCache::persistent(const void* host, std::size_t bytes, std::uint64_t version, const char* what) {
  if (!host || bytes == 0) return nullptr;
  auto it = mirrors_.find(host);
  if (it != mirrors_.end() && it->second.bytes == bytes && it->second.version == version) {
    it->second.used = true;
    return it->second.device;
  }
  if (it != mirrors_.end()) {
    // A mirror handed out earlier in this frame may still be read through a
    // view copied for this frame (one host array under two versions: the
    // scene's volume also a mesh's texture): it goes with the frame's copies.
    if (it->second.used) {
      frame_.emplace_back(it->second.device, it->second.bytes);
    } else {
      release(it->second.device, it->second.bytes);
    }
    mirrors_.erase(it);
  }
  Mirror mirror;
  mirror.device = allocate(bytes, what);
  mirror.bytes = bytes;
  mirror.version = version;
  mirror.used = true;
  try {
    memory_.upload(mirror.device, host, bytes);
  } catch (...) {
    release(mirror.device, bytes);
    throw;
  }
  mirrors_.emplace(host, mirror);
  ++uploads_;
  g_uploads.fetch_add(1);
  return mirror.device;
}

void* DeviceCache::frame(const void* host, std::size_t bytes, const char* what) {
  if (!host || bytes == 0) return nullptr;
  void* device = allocate(bytes, what);
  frame_.emplace_back(device, bytes);
  memory_.upload(device, host, bytes);
  return device;
}

void* DeviceCache::frame_zeroed(std::size_t bytes, const char* what) {
  void* device = allocate(bytes, what);
  frame_.emplace_back(device, bytes);
  memory_.zero(device, bytes);
  return device;
}

void* DeviceCache::scratch(std::size_t bytes, const char* what) {
  if (bytes <= scratch_bytes_) return scratch_;
  if (scratch_) release(scratch_, scratch_bytes_);
  scratch_ = nullptr;
  scratch_bytes_ = 0;
  scratch_ = allocate(bytes, what);
  scratch_bytes_ = bytes;
  return scratch_;
}

}  // namespace penumbra

#include "penumbra/backends/device.h"

#include "penumbra/base/error.h"

#include <atomic>
#include <cstdio>
#include <mutex>
#include <set>
#include <string>

namespace penumbra {
namespace {

std::atomic<DeviceMode> g_mode{DeviceMode::Auto};
std::atomic<std::uint64_t> g_device_budget{0};

}  // namespace

DeviceMode parse_device_mode(const std::string& text) {
  if (text == "auto") return DeviceMode::Auto;
  if (text == "cpu") return DeviceMode::Cpu;
  if (text == "cuda") {
    if (!cuda_built()) throw InvalidArgument("--device", "'cuda': this build has no CUDA backend (nvcc was not found)");
    if (cuda_device_count() == 0) throw InvalidArgument("--device", "'cuda': no CUDA device is present");
    return DeviceMode::Cuda;
  }
  throw InvalidArgument("--device", "'" + text + "' is not one of: auto, cpu, cuda");
}

void set_device_mode(DeviceMode mode) { g_mode.store(mode); }
DeviceMode device_mode() { return g_mode.load(); }

Device active_device() {
  switch (g_mode.load()) {
    case DeviceMode::Cpu: return Device::Cpu;
    case DeviceMode::Cuda: return Device::Cuda;
    case DeviceMode::Auto: break;
  }
  static const bool has_cuda = cuda_built() && cuda_device_count() > 0;
  return has_cuda ? Device::Cuda : Device::Cpu;
}

const char* to_string(Device device) { return device == Device::Cuda ? "cuda" : "cpu"; }

std::uint64_t device_memory_budget_bytes() { return g_device_budget.load(); }
void set_device_memory_budget_bytes(std::uint64_t bytes) { g_device_budget.store(bytes); }

void note_cpu_fallback(const char* what) {
  static std::mutex mutex;
  static std::set<std::string> told;
  const std::lock_guard<std::mutex> lock(mutex);
  if (told.insert(what).second) std::fprintf(stderr, "penumbra: %s has no CUDA path; it renders on the CPU\n", what);
}

#if !defined(PENUMBRA_HAVE_CUDA)
bool cuda_built() { return false; }
int cuda_device_count() { return 0; }
std::string cuda_device_name() { return ""; }
#endif

}  // namespace penumbra

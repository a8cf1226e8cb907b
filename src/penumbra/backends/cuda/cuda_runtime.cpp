// The CUDA half of backends/device.h and device_cache.h: what the driver
// reports, and device memory through the runtime API.
#include "penumbra/backends/cuda/device_cache.h"
#include "penumbra/backends/device.h"
#include "penumbra/base/error.h"

#include <cuda_runtime_api.h>

#include <string>

namespace penumbra {
namespace {

class CudaMemory final : public DeviceMemory {
 public:
  void* allocate(std::size_t bytes, const char* what) const override {
    std::size_t free_bytes = 0, total_bytes = 0;
    check_cuda(cudaMemGetInfo(&free_bytes, &total_bytes), "cudaMemGetInfo");
    if (bytes > free_bytes) {
      throw OutOfMemoryBudget(std::string("CUDA device memory for ") + what + " (what the device has free)", bytes,
                              free_bytes);
    }
    void* device = nullptr;
    const cudaError_t status = cudaMalloc(&device, bytes);
    if (status == cudaErrorMemoryAllocation) {
      cudaGetLastError();  // clears it
      throw OutOfMemoryBudget(std::string("CUDA device memory for ") + what, bytes, free_bytes);
    }
    check_cuda(status, "cudaMalloc");
    return device;
  }
  void release(void* device) const override { cudaFree(device); }
  void upload(void* device, const void* host, std::size_t bytes) const override {
    check_cuda(cudaMemcpy(device, host, bytes, cudaMemcpyHostToDevice), "cudaMemcpy (upload)");
  }
  void zero(void* device, std::size_t bytes) const override {
    check_cuda(cudaMemset(device, 0, bytes), "cudaMemset");
  }
};

}  // namespace

void check_cuda(int status, const char* call) {
  if (status == cudaSuccess) return;
  throw Error(std::string("cuda: ") + call + ": " + cudaGetErrorString(cudaError_t(status)));
}

const DeviceMemory& cuda_memory() {
  static const CudaMemory memory;
  return memory;
}

bool cuda_built() { return true; }

int cuda_device_count() {
  int count = 0;
  // Without a driver or a GPU this fails (no device, insufficient driver): 0.
  if (cudaGetDeviceCount(&count) != cudaSuccess) {
    cudaGetLastError();
    return 0;
  }
  return count;
}

std::string cuda_device_name() {
  if (cuda_device_count() == 0) return "";
  cudaDeviceProp properties{};
  if (cudaGetDeviceProperties(&properties, 0) != cudaSuccess) return "";
  return properties.name;
}

}  // namespace penumbra

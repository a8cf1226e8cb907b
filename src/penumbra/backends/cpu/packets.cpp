#include "penumbra/backends/cpu/packets.h"

#include "penumbra/base/error.h"
#include "penumbra/volume/volume_sampler.h"

// Only the run-time CPU query is used here; a single static target keeps
// Highway 1.0.3's target detection quiet under -march=native.
#define HWY_COMPILE_ONLY_STATIC
#include <hwy/targets.h>

#include <atomic>
#include <cstdint>

namespace penumbra {
namespace {

std::atomic<SimdMode> g_mode{SimdMode::Auto};

bool built(SimdTarget target) {
  switch (target) {
    case SimdTarget::Scalar: return true;
#if defined(PENUMBRA_SIMD_AVX2)
    case SimdTarget::Avx2: break;
#else
    case SimdTarget::Avx2: return false;
#endif
#if defined(PENUMBRA_SIMD_AVX3)
    case SimdTarget::Avx3: break;
#else
    case SimdTarget::Avx3: return false;
#endif
  }
#if defined(PENUMBRA_SIMD_AVX2) || defined(PENUMBRA_SIMD_AVX3)
  const std::int64_t cpu = hwy::SupportedTargets();
  if (target == SimdTarget::Avx2) return (cpu & HWY_AVX2) != 0;
  return (cpu & HWY_AVX3) != 0;
#else
  return false;
#endif
}

}  // namespace

SimdMode parse_simd_mode(const std::string& text) {
  SimdMode mode;
  SimdTarget needs = SimdTarget::Scalar;
  if (text == "auto") {
    mode = SimdMode::Auto;
  } else if (text == "off") {
    mode = SimdMode::Off;
  } else if (text == "avx2") {
    mode = SimdMode::Avx2;
    needs = SimdTarget::Avx2;
  } else if (text == "avx512") {
    mode = SimdMode::Avx3;
    needs = SimdTarget::Avx3;
  } else {
    throw InvalidArgument("--simd", "'" + text + "' is not one of: auto, off, avx2, avx512");
  }
  if (!built(needs)) {
    throw InvalidArgument("--simd", "'" + text + "' is not available: this CPU or this build lacks it (available: " +
                                        std::string(to_string(active_simd_target())) + " and below)");
  }
  return mode;
}

void set_simd_mode(SimdMode mode) { g_mode.store(mode); }
SimdMode simd_mode() { return g_mode.load(); }

SimdTarget active_simd_target() {
  switch (g_mode.load()) {
    case SimdMode::Off: return SimdTarget::Scalar;
    case SimdMode::Avx2: return built(SimdTarget::Avx2) ? SimdTarget::Avx2 : SimdTarget::Scalar;
    case SimdMode::Avx3: return built(SimdTarget::Avx3) ? SimdTarget::Avx3 : SimdTarget::Scalar;
    case SimdMode::Auto: break;
  }
  if (built(SimdTarget::Avx3)) return SimdTarget::Avx3;
  if (built(SimdTarget::Avx2)) return SimdTarget::Avx2;
  return SimdTarget::Scalar;
}

const char* to_string(SimdTarget target) {
  switch (target) {
    case SimdTarget::Avx3: return "avx512";
    case SimdTarget::Avx2: return "avx2";
    case SimdTarget::Scalar: break;
  }
  return "scalar";
}

int simd_width(SimdTarget target) {
  switch (target) {
    case SimdTarget::Avx3: return 16;
    case SimdTarget::Avx2: return 8;
    case SimdTarget::Scalar: break;
  }
  return 1;
}

SimdTarget packet_target(const RenderView& view) {
  const SimdTarget target = active_simd_target();
  if (target == SimdTarget::Scalar) return target;
  const VolumeView& volume = view.volume;
  if (!volume.data || !packet_voxel_type(volume.type)) return SimdTarget::Scalar;
  const std::uint64_t voxels = std::uint64_t(volume.dims.x) * std::uint64_t(volume.dims.y) * std::uint64_t(volume.dims.z);
  // Packet offsets are 32-bit: voxel bytes, and the 4-byte normal texels.
  constexpr std::uint64_t limit = (std::uint64_t(1) << 31) - 64;
  if (voxels * voxel_size(volume.type) >= limit || voxels * voxel_size(volume.type) < 4) return SimdTarget::Scalar;
  if (view.normals.texels && voxels * 4 >= limit) return SimdTarget::Scalar;
  return target;
}

}  // namespace penumbra

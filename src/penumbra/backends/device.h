#pragma once
// Which device renders (`--device cpu|cuda|auto`), and how a Lighting reaches
// the CUDA backend. The choice is process-wide, like `--simd`
// (backends/cpu/packets.h).
//
// A Lighting renders on CUDA when its header declares it with
// PENUMBRA_DEVICE_LIGHTING(type) and its technique's .cu unit instantiates it
// with PENUMBRA_INSTANTIATE_DEVICE(type) (backends/cuda/launch.cuh). The
// declaration expands to nothing in builds without CUDA, so the trait is
// false there and every technique renders on the CPU. A Lighting that is not
// declared renders on the CPU even when CUDA is active (render_image says so
// once per process on stderr).
//
// A device Lighting has, besides its kernel operator()s, a host member
//   template <class Mirror> Lighting on_device(Mirror& m) const
// returning a copy whose pointers point into device memory (Mirror is the
// CUDA backend's DeviceMirror; see backends/cuda/device_mirror.h).
#include "penumbra/render/image.h"
#include "penumbra/render/render_view.h"

#include <cstdint>
#include <string>
#include <type_traits>

namespace penumbra {

enum class Device : std::uint8_t { Cpu, Cuda };
enum class DeviceMode : std::uint8_t { Auto, Cpu, Cuda };

// "auto", "cpu", "cuda" (throws InvalidArgument naming `--device` for
// anything else, and for "cuda" when the build has no CUDA backend or no
// device is present).
DeviceMode parse_device_mode(const std::string& text);
void set_device_mode(DeviceMode mode);
DeviceMode device_mode();

// The device renders run on: the mode's device; for Auto, CUDA when the
// build has the backend and a device is present, else the CPU.
Device active_device();
const char* to_string(Device device);

// Whether this build has the CUDA backend, how many CUDA devices the driver
// reports (0 without a driver or a GPU), and the first one's name ("" when
// none).
bool cuda_built();
int cuda_device_count();
std::string cuda_device_name();

// The most device memory one technique's mirrors may hold (0, the default:
// no limit but the memory the device has free). Above it, rendering throws
// OutOfMemoryBudget naming what needed the memory.
std::uint64_t device_memory_budget_bytes();
void set_device_memory_budget_bytes(std::uint64_t bytes);

template <class Lighting> struct DeviceLighting : std::false_type {};

struct RayStats;

// Renders every pixel of `view` into `image` on the CUDA device with
// Lighting, adding the samples taken to `stats`. Defined only in .cu units
// (PENUMBRA_INSTANTIATE_DEVICE).
template <class Lighting>
void render_device(const RenderView& view, const Lighting& lighting, Image& image, RayStats& stats);

// Prints, once per Lighting type, that a technique renders on the CPU while
// CUDA is active.
void note_cpu_fallback(const char* what);

}  // namespace penumbra

#if defined(PENUMBRA_HAVE_CUDA)
// Declares that `...` (a Lighting type) renders on CUDA; at namespace scope in
// namespace penumbra.
#define PENUMBRA_DEVICE_LIGHTING(...) \
  template <> struct DeviceLighting<__VA_ARGS__> : std::true_type {}
#else
#define PENUMBRA_DEVICE_LIGHTING(...) static_assert(true)
#endif

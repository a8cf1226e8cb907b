#pragma once
// The CPU backend's packet path, as render_image (render/render_loop.h) sees
// it: which instruction set packets run on, and the per-target entry points
// that the SIMD units (cmake/PenumbraSimd.cmake) instantiate.
//
// A Lighting gets the packet path when its header declares it with
// PENUMBRA_PACKET_LIGHTING(type) and one SIMD source of its technique
// instantiates it with PENUMBRA_INSTANTIATE_PACKETS(type) (packet_render.h).
// A declaration without the instantiation fails to link, so the two cannot
// drift apart silently; a Lighting that is not declared renders on the
// scalar path.
#include "penumbra/render/image.h"
#include "penumbra/render/render_view.h"

#include <cstdint>
#include <string>
#include <type_traits>

namespace penumbra {

enum class SimdTarget : std::uint8_t { Scalar, Avx2, Avx3 };

// What the user asks for (`--simd`): the best target this CPU and build
// support, none, or one in particular.
enum class SimdMode : std::uint8_t { Auto, Off, Avx2, Avx3 };

// "auto", "off", "avx2", "avx512" (throws InvalidArgument naming `--simd`
// for anything else, or for a target this CPU or build lacks).
SimdMode parse_simd_mode(const std::string& text);
void set_simd_mode(SimdMode mode);
SimdMode simd_mode();

// The target packets run on under the current mode on this CPU: Scalar when
// the mode is off or the build has no SIMD units. "avx512", "avx2", "scalar".
SimdTarget active_simd_target();
const char* to_string(SimdTarget target);
// Lanes per packet of a target (1 for Scalar).
int simd_width(SimdTarget target);

// The target a render of `view` takes: active_simd_target(), or Scalar when
// the view cannot run as packets (voxel types without a 32-bit gather,
// volumes whose voxel or normal offsets pass 2^31 bytes, grids under 4
// bytes).
SimdTarget packet_target(const RenderView& view);

// The function a SIMD unit defines for `target`, or nullptr where this build
// has no unit of that target: pick.template operator()<T>() names the
// function of target T, e.g. []<SimdTarget T>() { return &march<T>; }. Only
// for scalar units: a SIMD unit must not name another target's function.
template <class Pick> auto simd_unit_function(SimdTarget target, const Pick& pick) {
  using Function = decltype(pick.template operator()<SimdTarget::Scalar>());
  switch (target) {
#if defined(PENUMBRA_SIMD_AVX3)
    case SimdTarget::Avx3: return Function(pick.template operator()<SimdTarget::Avx3>());
#endif
#if defined(PENUMBRA_SIMD_AVX2)
    case SimdTarget::Avx2: return Function(pick.template operator()<SimdTarget::Avx2>());
#endif
    default: return Function(nullptr);
  }
}

template <class Lighting> struct PacketLighting : std::false_type {};

struct RayStats;

// Renders every pixel of `view` into `image` with Lighting's packet form on
// `Target`, adding the samples and packet steps taken to `stats`. Defined
// only in the SIMD units of Target (packet_render.h).
template <SimdTarget Target, class Lighting>
void render_packets(const RenderView& view, const Lighting& lighting, Image& image, RayStats& stats);

}  // namespace penumbra

// Declares that `...` (a Lighting type) has a packet path; at namespace scope
// in namespace penumbra.
#define PENUMBRA_PACKET_LIGHTING(...) \
  template <> struct PacketLighting<__VA_ARGS__> : std::true_type {}

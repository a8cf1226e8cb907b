#pragma once
// The scalar types a volume may store, and a dispatch from the runtime tag to
// the C++ type.
#include "penumbra/base/hd.h"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

namespace penumbra {

enum class VoxelType : std::uint8_t { UInt8, Int8, UInt16, Int16, UInt32, Int32, Float32, Float64 };

PENUMBRA_HD constexpr std::size_t voxel_size(VoxelType type) {
  switch (type) {
    case VoxelType::UInt8:
    case VoxelType::Int8: return 1;
    case VoxelType::UInt16:
    case VoxelType::Int16: return 2;
    case VoxelType::UInt32:
    case VoxelType::Int32:
    case VoxelType::Float32: return 4;
    case VoxelType::Float64: return 8;
  }
  return 0;
}

// "uint8", "int16", "float32", ...
std::string_view to_string(VoxelType type);
std::optional<VoxelType> voxel_type_from_string(std::string_view name);

template <class T> struct VoxelTypeOf;
template <> struct VoxelTypeOf<std::uint8_t> { static constexpr VoxelType value = VoxelType::UInt8; };
template <> struct VoxelTypeOf<std::int8_t> { static constexpr VoxelType value = VoxelType::Int8; };
template <> struct VoxelTypeOf<std::uint16_t> { static constexpr VoxelType value = VoxelType::UInt16; };
template <> struct VoxelTypeOf<std::int16_t> { static constexpr VoxelType value = VoxelType::Int16; };
template <> struct VoxelTypeOf<std::uint32_t> { static constexpr VoxelType value = VoxelType::UInt32; };
template <> struct VoxelTypeOf<std::int32_t> { static constexpr VoxelType value = VoxelType::Int32; };
template <> struct VoxelTypeOf<float> { static constexpr VoxelType value = VoxelType::Float32; };
template <> struct VoxelTypeOf<double> { static constexpr VoxelType value = VoxelType::Float64; };

// Calls f(T{}) with T the C++ type of `type`.
template <class F> PENUMBRA_HD decltype(auto) visit_voxel_type(VoxelType type, F&& f) {
  switch (type) {
    case VoxelType::UInt8: return f(std::uint8_t{});
    case VoxelType::Int8: return f(std::int8_t{});
    case VoxelType::UInt16: return f(std::uint16_t{});
    case VoxelType::Int16: return f(std::int16_t{});
    case VoxelType::UInt32: return f(std::uint32_t{});
    case VoxelType::Int32: return f(std::int32_t{});
    case VoxelType::Float32: return f(float{});
    case VoxelType::Float64: break;
  }
  return f(double{});
}

}  // namespace penumbra

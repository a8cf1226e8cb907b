#include "penumbra/volume/voxel_type.h"

#include <array>
#include <utility>

namespace penumbra {
namespace {

constexpr std::array<std::pair<VoxelType, std::string_view>, 8> kNames{{
    {VoxelType::UInt8, "uint8"},
    {VoxelType::Int8, "int8"},
    {VoxelType::UInt16, "uint16"},
    {VoxelType::Int16, "int16"},
    {VoxelType::UInt32, "uint32"},
    {VoxelType::Int32, "int32"},
    {VoxelType::Float32, "float32"},
    {VoxelType::Float64, "float64"},
}};

}  // namespace

std::string_view to_string(VoxelType type) {
  for (const auto& [t, name] : kNames) {
    if (t == type) return name;
  }
  return "unknown";
}

std::optional<VoxelType> voxel_type_from_string(std::string_view name) {
  for (const auto& [t, n] : kNames) {
    if (n == name) return t;
  }
  return std::nullopt;
}

}  // namespace penumbra

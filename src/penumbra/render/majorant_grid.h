#pragma once
// MajorantGrid: for one transfer function, the largest extinction any sample
// inside each macrocell can have (0 = the macrocell is empty), and for empty
// macrocells the chessboard distance, in macrocells, to the nearest non-empty
// one. The marching loop skips whole cubes of empty macrocells with it; the
// path tracer uses the majorants for delta and ratio tracking.
#include "penumbra/scene/transfer_function.h"
#include "penumbra/volume/macrocell_grid.h"

#include <cstdint>
#include <vector>

namespace penumbra {

struct MajorantGrid {
  std::vector<float> majorant;                // per macrocell, x fastest
  std::vector<std::uint8_t> empty_distance;  // 0 for non-empty cells, else >= 1, capped at 255

  std::uint64_t bytes() const { return majorant.size() * (sizeof(float) + sizeof(std::uint8_t)); }
};

MajorantGrid build_majorant_grid(const MacrocellGrid& grid, const TransferFunctionTable& table);

// Chessboard (L-infinity) distance transform of the empty cells: for each
// empty cell, 1 + the number of rings of empty cells around it. Exposed for
// tests.
std::vector<std::uint8_t> empty_space_distance(const std::vector<float>& majorant, ivec3 dims);

}  // namespace penumbra

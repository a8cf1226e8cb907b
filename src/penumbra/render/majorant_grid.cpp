#include "penumbra/render/majorant_grid.h"

#include "penumbra/base/parallel.h"

#include <algorithm>

namespace penumbra {

std::vector<std::uint8_t> empty_space_distance(const std::vector<float>& majorant, ivec3 dims) {
  // Two raster passes over the 26-neighbourhood (Rosenfeld & Pfaltz) give the
  // exact chessboard distance to the nearest non-empty cell.
  std::vector<int> d(majorant.size());
  const int far = 255;
  for (std::size_t i = 0; i < majorant.size(); ++i) d[i] = majorant[i] > 0.0f ? 0 : far;
  auto index = [&](int x, int y, int z) { return std::size_t(x + dims.x * (y + std::int64_t(dims.y) * z)); };
  auto relax = [&](int x, int y, int z, int sign) {
    int& here = d[index(x, y, z)];
    if (here == 0) return;
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          // Forward pass: neighbours already visited (earlier in raster order).
          const int order = dz * 9 + dy * 3 + dx;
          if (order * sign >= 0) continue;
          const int nx = x + dx, ny = y + dy, nz = z + dz;
          if (nx < 0 || ny < 0 || nz < 0 || nx >= dims.x || ny >= dims.y || nz >= dims.z) continue;
          here = std::min(here, d[index(nx, ny, nz)] + 1);
        }
  };
  for (int z = 0; z < dims.z; ++z)
    for (int y = 0; y < dims.y; ++y)
      for (int x = 0; x < dims.x; ++x) relax(x, y, z, 1);
  for (int z = dims.z - 1; z >= 0; --z)
    for (int y = dims.y - 1; y >= 0; --y)
      for (int x = dims.x - 1; x >= 0; --x) relax(x, y, z, -1);
  std::vector<std::uint8_t> out(d.size());
  for (std::size_t i = 0; i < d.size(); ++i) out[i] = std::uint8_t(std::min(d[i], far));
  return out;
}

MajorantGrid build_majorant_grid(const MacrocellGrid& grid, const TransferFunctionTable& table) {
  MajorantGrid m;
  const ivec3 d = grid.dims();
  m.majorant.resize(static_cast<std::size_t>(d.x) * d.y * d.z);
  const MacrocellView cells = grid.view();
  parallel_for(0, std::int64_t(m.majorant.size()), [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t i = first; i < last; ++i) {
      const vec2 range = cells.min_max[i];
      m.majorant[static_cast<std::size_t>(i)] = table.max_extinction(range.x, range.y);
    }
  }, 256);
  m.empty_distance = empty_space_distance(m.majorant, d);
  return m;
}

}  // namespace penumbra

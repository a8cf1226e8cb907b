#pragma once
// The CPU backend's one way of running kernels in parallel (TBB underneath).
// Kernels are written as bodies over index ranges; a CUDA backend would launch
// the same per-item functions instead.
#include <cstdint>
#include <functional>

namespace penumbra {

// Runs body(begin_chunk, end_chunk) over disjoint chunks that cover
// [begin, end). `grain` is the smallest chunk worth scheduling.
void parallel_for(std::int64_t begin, std::int64_t end,
                  const std::function<void(std::int64_t, std::int64_t)>& body, std::int64_t grain = 1);

// Runs body(x0, y0, x1, y1) over square tiles of `tile` pixels covering a
// width x height image, in parallel.
void parallel_for_tiles(int width, int height, int tile,
                        const std::function<void(int, int, int, int)>& body);

// The same with a plain function and context pointer: for code compiled
// with other instruction-set flags (the SIMD units of backends/cpu), which
// must not instantiate std::function's members itself.
using TileFunction = void (*)(void* context, int x0, int y0, int x1, int y1);
void parallel_for_tiles(int width, int height, int tile, TileFunction body, void* context);

// Limits the worker threads of every later parallel_for (0 = all cores).
void set_thread_count(int threads);
int thread_count();

}  // namespace penumbra

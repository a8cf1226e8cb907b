#include "penumbra/base/parallel.h"

#include "penumbra/base/error.h"

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>

#include <memory>
#include <mutex>

namespace penumbra {
namespace {

std::mutex g_control_mutex;
std::unique_ptr<tbb::global_control> g_control;
int g_threads = 0;

}  // namespace

void parallel_for(std::int64_t begin, std::int64_t end,
                  const std::function<void(std::int64_t, std::int64_t)>& body, std::int64_t grain) {
  if (end <= begin) return;
  tbb::parallel_for(tbb::blocked_range<std::int64_t>(begin, end, grain > 0 ? grain : 1),
                    [&](const tbb::blocked_range<std::int64_t>& r) { body(r.begin(), r.end()); });
}

void parallel_for_tiles(int width, int height, int tile, const std::function<void(int, int, int, int)>& body) {
  if (width <= 0 || height <= 0) return;
  if (tile <= 0) tile = 16;
  const int tiles_x = (width + tile - 1) / tile;
  const int tiles_y = (height + tile - 1) / tile;
  parallel_for(0, std::int64_t(tiles_x) * tiles_y, [&](std::int64_t first, std::int64_t last) {
    for (std::int64_t t = first; t < last; ++t) {
      const int x0 = int(t % tiles_x) * tile;
      const int y0 = int(t / tiles_x) * tile;
      body(x0, y0, std::min(x0 + tile, width), std::min(y0 + tile, height));
    }
  });
}

void parallel_for_tiles(int width, int height, int tile, TileFunction body, void* context) {
  parallel_for_tiles(width, height, tile, [&](int x0, int y0, int x1, int y1) { body(context, x0, y0, x1, y1); });
}

void set_thread_count(int threads) {
  if (threads < 0) throw InvalidArgument("threads", "must be >= 0 (0 = all cores)");
  std::lock_guard lock(g_control_mutex);
  g_control.reset();
  if (threads > 0) {
    g_control = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                      static_cast<std::size_t>(threads));
  }
  g_threads = threads;
}

int thread_count() {
  std::lock_guard lock(g_control_mutex);
  if (g_threads > 0) return g_threads;
  return static_cast<int>(tbb::info::default_concurrency());
}

}  // namespace penumbra

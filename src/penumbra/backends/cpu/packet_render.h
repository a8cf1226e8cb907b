#pragma once
// The packet image loop of one SIMD target: the tiles of render_image
// (render/render_loop.h), each a stream of rays that march W at a time
// through march_rays<SimdLanes>, the same loop the scalar path runs with one
// lane.
//
// Include this only in a technique's SIMD source (built once per target by
// penumbra_simd_sources, cmake/PenumbraSimd.cmake) and instantiate each
// Lighting that the technique declares with PENUMBRA_PACKET_LIGHTING:
//   PENUMBRA_INSTANTIATE_PACKETS(ScatteringLighting<MyVisibility>);
//
// Everything this unit compiles must end up with a name of its own target,
// or be inlined: an inline function compiled here with AVX-512 and kept out
// of line could be the copy the linker keeps for the scalar path. So the
// tile body is `flatten` (every call inlined into it), it reaches TBB through
// a function pointer rather than std::function, and the
// simd_units_define_only_target_symbols test (scripts/check-simd-symbols.sh) checks the objects' weak symbols.
#include "penumbra/backends/cpu/packets.h"
#include "penumbra/backends/cpu/simd_lanes.h"
#include "penumbra/base/parallel.h"
#include "penumbra/render/lighting.h"
#include "penumbra/render/render_loop.h"
#include "penumbra/volume/volume_sampler.h"

#include <atomic>
#include <cstdint>

namespace penumbra {

namespace HWY_NAMESPACE {

template <class Lighting> struct PacketImage {
  const RenderView* view;
  const Lighting* lighting;
  AnyVoxelSampler sampler;
  Image* image;
  std::atomic<std::uint64_t>* samples;
  std::atomic<std::uint64_t>* steps;
};

// The pixels of one tile as a ray stream for march_rays, in blocks of
// 4 x (W / 4) pixels so that the first packet is a compact block and later
// rays come from nearby.
struct TileRays {
  const RenderView* view;
  Image* image;
  int x0, y0, x1, y1;
  int block_width, block_height;
  int block_x, block_y, in_block = 0;

  TileRays(const RenderView& v, Image& img, int tx0, int ty0, int tx1, int ty1, int lanes)
      : view(&v), image(&img), x0(tx0), y0(ty0), x1(tx1), y1(ty1), block_width(4), block_height(lanes / 4),
        block_x(tx0), block_y(ty0) {}

  HWY_INLINE bool next(Ray& ray, float& offset, int& id) {
    for (;;) {
      if (block_y >= y1) return false;
      const int x = block_x + in_block % block_width, y = block_y + in_block / block_width;
      if (++in_block == block_width * block_height) {
        in_block = 0;
        block_x += block_width;
        if (block_x >= x1) {
          block_x = x0;
          block_y += block_height;
        }
      }
      if (x >= x1 || y >= y1) continue;
      ray = view->camera.pixel_ray(float(x) + 0.5f, float(y) + 0.5f, view->width, view->height);
      offset = pixel_sample_offset(*view, x, y);
      id = y * view->width + x;
      return true;
    }
  }
  HWY_INLINE void finish(int id, vec4 result) { image->at(id % view->width, id / view->width) = result; }
};

template <class Lighting>
__attribute__((flatten)) void render_packet_tile(void* context, int x0, int y0, int x1, int y1) {
  using L = SimdLanes;
  const PacketImage<Lighting>& job = *static_cast<const PacketImage<Lighting>*>(context);
  TileRays rays(*job.view, *job.image, x0, y0, x1, y1, L::kWidth);
  RayStats stats;
  march_rays<L>(*job.view, job.sampler, rays, *job.lighting, stats);
  job.samples->fetch_add(stats.samples, std::memory_order_relaxed);
  job.steps->fetch_add(stats.steps, std::memory_order_relaxed);
}

}  // namespace HWY_NAMESPACE

template <SimdTarget Target, class Lighting>
void render_packets(const RenderView& view, const Lighting& lighting, Image& image, RayStats& stats) {
  static_assert(Target == HWY_NAMESPACE::kThisSimdTarget, "each SIMD unit instantiates its own target only");
  std::atomic<std::uint64_t> samples{0}, steps{0};
  HWY_NAMESPACE::PacketImage<Lighting> job{&view,  &lighting, AnyVoxelSampler(view.volume.data, view.volume.dims, view.volume.type),
                                           &image, &samples,  &steps};
  parallel_for_tiles(view.width, view.height, 16, &HWY_NAMESPACE::render_packet_tile<Lighting>, &job);
  stats.samples += samples.load();
  stats.steps += steps.load();
}

}  // namespace penumbra

// Instantiates the packet path of one Lighting type (its name as seen from
// namespace penumbra) for this unit's target; at global scope.
#define PENUMBRA_INSTANTIATE_PACKETS(...)                                                      \
  using namespace penumbra;                                                                    \
  template void penumbra::render_packets<penumbra::HWY_NAMESPACE::kThisSimdTarget, __VA_ARGS__>( \
      const penumbra::RenderView&, const __VA_ARGS__&, penumbra::Image&, penumbra::RayStats&)

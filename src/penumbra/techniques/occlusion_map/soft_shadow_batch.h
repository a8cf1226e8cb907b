#pragma once
// occlusion-map's soft shadows as packets on the CPU. A soft-shadow march
// runs from one surface point, so the isosurface loop cannot give it lanes
// one pixel at a time; instead a tile is shaded in two passes:
//  1. every pixel's hit is shaded with the soft-shadow visibility deferred:
//     per light, the shading with only that light visible (the lighting is
//     linear in each light's visibility) is that light's share of the pixel,
//     and the visibility records its march (SoftShadowQueries::record);
//  2. the tile's marches run 8 or 16 at a time through
//     OcclusionQueries::soft_shadow_lanes on SIMD lanes
//     (occlusion_map_packets.cpp), and each share is added to its pixel
//     scaled by its march's visibility.
// The scalar path and the CUDA device run the same march per pixel with one
// lane (OcclusionQueries::soft_shadow).
#include "penumbra/backends/cpu/packets.h"
#include "penumbra/techniques/occlusion_map/occlusion_queries.h"

#include <vector>

namespace penumbra {

// The marches of one tile, structure of arrays.
struct SoftShadowQueries {
  enum Field : int { Px, Py, Pz, Nx, Ny, Nz, Lx, Ly, Lz, Distance, Spread, Own, kFields };
  float* fields = nullptr;  // kFields arrays of `capacity` floats
  vec3* shares = nullptr;   // per march: its light's share of the pixel
  int* pixels = nullptr;    // per march: the pixel it darkens (row-major index)
  int capacity = 0;         // a multiple of the widest packet
  int count = 0;
  int light = -1;  // the light whose share is being shaded (the others are dark meanwhile)
  int pixel = -1;  // the pixel being shaded

  PENUMBRA_HD float* field(int f) const { return fields + f * capacity; }

  // The march of the pixel being shaded toward light `light` (see
  // OcclusionQueries::soft_shadow for the arguments).
  PENUMBRA_HD void record(vec3 p, vec3 n, vec3 to_light, float distance, float spread, float own) {
    const int i = count++;
    const float values[kFields] = {p.x,        p.y,        p.z,        n.x,      n.y,    n.z,
                                   to_light.x, to_light.y, to_light.z, distance, spread, own};
    for (int f = 0; f < kFields; ++f) field(f)[i] = values[f];
    pixels[i] = pixel;
    shares[i] = vec3(0.0f);
  }

  // Shades a point once per light with only that light visible (shade()
  // returns the point's light from the lights, without the ambient term) and
  // keeps each recorded march's share. Returns the sum of the shares that
  // recorded no march (a light read from a plane's shadow grid, or none).
  template <class Shade> PENUMBRA_HD vec3 defer_lights(int light_count, Shade&& shade) {
    vec3 known(0.0f);
    for (int i = 0; i < light_count; ++i) {
      light = i;
      const int before = count;
      const vec3 share = shade();
      if (count > before) {
        shares[before] = share;
      } else {
        known += share;
      }
    }
    light = -1;
    return known;
  }
};

// The storage behind a tile's SoftShadowQueries.
class SoftShadowBatch {
 public:
  // Room for every pixel of a tile of `pixels` toward each of `lights` lights.
  SoftShadowBatch(int pixels, int lights) {
    const int marches = pixels * lights;
    capacity_ = (marches + kMaxWidth - 1) / kMaxWidth * kMaxWidth;
    fields_.assign(std::size_t(capacity_) * SoftShadowQueries::kFields, 0.0f);
    shares_.assign(std::size_t(capacity_), vec3(0.0f));
    pixels_.assign(std::size_t(capacity_), 0);
    visibility_.assign(std::size_t(capacity_), 1.0f);
  }
  SoftShadowQueries queries() {
    SoftShadowQueries q;
    q.fields = fields_.data();
    q.shares = shares_.data();
    q.pixels = pixels_.data();
    q.capacity = capacity_;
    return q;
  }
  float* visibility() { return visibility_.data(); }

  // Fills the marches from `count` to the next multiple of the widest packet
  // with marches that take no step (distance 0), so packets read whole.
  static void pad(SoftShadowQueries& q) {
    const int end = (q.count + kMaxWidth - 1) / kMaxWidth * kMaxWidth;
    for (int i = q.count; i < end; ++i) {
      for (int f = 0; f < SoftShadowQueries::kFields; ++f) q.field(f)[i] = 0.0f;
      q.field(SoftShadowQueries::Nz)[i] = 1.0f;
      q.field(SoftShadowQueries::Lz)[i] = 1.0f;
      q.field(SoftShadowQueries::Own)[i] = -1.0f;
    }
  }

  static constexpr int kMaxWidth = 16;

 private:
  int capacity_ = 0;
  std::vector<float> fields_;
  std::vector<vec3> shares_;
  std::vector<int> pixels_;
  std::vector<float> visibility_;
};

// Marches queries[0, count) (padded by SoftShadowBatch::pad) as packets of
// Target and writes each one's visibility to out. Defined only in the SIMD
// units of Target (occlusion_map_packets.cpp).
template <SimdTarget Target>
void march_soft_shadows(const OcclusionQueries<2>& queries, float t, const SoftShadowQueries& batch, float* out);
using SoftShadowMarch = void (*)(const OcclusionQueries<2>&, float, const SoftShadowQueries&, float*);

}  // namespace penumbra

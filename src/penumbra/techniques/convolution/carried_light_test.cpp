#include "penumbra/techniques/convolution/carried_light.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace penumbra {
namespace carried_light_test {  // named: the test sources build as unity files
namespace {

constexpr int kW = 48, kH = 32;

SlabFrame perspective_frame(bool orthographic = false) {
  SlabFrame f;
  f.camera = Camera{vec3(0.0f, 0.0f, 40.0f), vec3(0.0f), vec3(0.0f, 1.0f, 0.0f), 30.0f,
                    orthographic ? Projection::Orthographic : Projection::Perspective, 20.0f}
                 .view();
  f.width = kW;
  f.height = kH;
  f.slab_distance = 0.5f;
  return f;
}

// The light's lateral step per slab in world units (a tilted light).
const vec2 kTap(0.05f, -0.03f);
const float kUnitWeight = 1.0f;

// The zero-variance light's slab kernel: the one tap kTap.
SlabKernel single_tap_kernel() {
  SlabKernel k;
  k.taps = &kTap;
  k.weights = &kUnitWeight;
  k.count = 1;
  k.mean = kTap;
  return k;
}

struct Carried {
  CarriedGrid grid;
  std::vector<float> texels[2];
  int half = 0;
  int rebases = 0;
};

// A vertical edge at frame x = x0 (dark left of it; x0 whole, half-way
// between two texel centres, where a bilinear read puts the step) on slab 0, carried from
// depth z0 over `slabs` slabs; returns the edge's analytic x on the last slab.
float carry_edge(Carried& c, const SlabFrame& f, float z0, int slabs, float x0, float min_scale) {
  c.grid = carried_grid(f.width, f.height, min_scale);
  const std::size_t n = std::size_t(c.grid.width) * std::size_t(c.grid.height);
  c.texels[0].assign(n, 1.0f);
  c.texels[1].assign(n, 1.0f);
  for (int y = 0; y < c.grid.height; ++y)
    for (int x = 0; x < c.grid.width; ++x) {
      if (c.grid.position(x, y).x < x0) c.texels[0][std::size_t(x + c.grid.width * y)] = 0.0f;
    }
  float edge = x0;
  for (int k = 1; k <= slabs; ++k) {
    const SlabMapping m = slab_mapping(f, z0 + float(k) * f.slab_distance);
    const vec2 w = m.pixels_per_unit * vec2(-kTap.x, kTap.y);
    advance_carried_grid(c.grid, m, w);
    edge = m.center.x + (edge - m.center.x - w.x) / m.scale;  // where slab k - 1's edge lands on slab k
    float* from = c.texels[c.half].data();
    float* to = c.texels[1 - c.half].data();
    bool moved = true;
    if (c.grid.scale < min_scale) {
      resample_carried_grid(c.grid, from, to, 1);
    } else {
      moved = shift_carried_grid(c.grid, from, to, 1) != ivec2(0);
    }
    if (moved) {
      c.half = 1 - c.half;
      ++c.rebases;
    }
  }
  return edge;
}

// A buffer's light along the frame row y = kH / 2 (continuous: bilinear reads
// every 1/64 pixel), as (frame x, light) samples.
constexpr float kStep = 1.0f / 64.0f;
template <class Read> std::vector<float> read_row(Read read) {
  std::vector<float> row;
  for (float x = 0.0f; x < float(kW); x += kStep) row.push_back(read(vec2(x, 0.5f * float(kH))));
  return row;
}

// Frame x where the row first rises through `level`.
float crossing(const std::vector<float>& row, float level) {
  for (std::size_t i = 1; i < row.size(); ++i) {
    if (row[i - 1] < level && row[i] >= level) {
      return kStep * (float(i) - 1.0f + (level - row[i - 1]) / (row[i] - row[i - 1]));
    }
  }
  return -1.0f;
}

// The grid follows the composed slab maps exactly: after 60 slabs of a
// perspective camera and a tilted light (integer shifts on the way, the grid
// shrinking to z_0 / z_60), the edge is where the maps put it and as sharp as
// one bilinear read of the grid (10-90 % over 0.8 texel). Re-sampling the
// same edge every slab, as the convolution does for soft lights, leaves it
// several pixels wide.
TEST(CarriedLight, AnEdgeRidesTheComposedSlabMapsUnblurred) {
  for (bool orthographic : {false, true}) {
    const SlabFrame f = perspective_frame(orthographic);
    Carried c;
    const float z0 = 30.0f;
    const int slabs = 60;
    const float min_scale = orthographic ? 1.0f : 0.98f * z0 / (z0 + float(slabs) * f.slab_distance);
    const float edge = carry_edge(c, f, z0, slabs, 21.0f, min_scale);
    const std::vector<float> row = read_row(
        [&](vec2 p) { return read_buffer(c.texels[c.half].data(), c.grid.width, c.grid.height, c.grid.texel_of(p)); });
    const float half = crossing(row, 0.5f), width = crossing(row, 0.9f) - crossing(row, 0.1f);
    std::printf("%s: edge at %.3f (maps: %.3f), 10-90 width %.3f px, scale %.3f, %d integer shifts\n",
                orthographic ? "orthographic" : "perspective", half, edge, width, c.grid.scale, c.rebases);
    EXPECT_NEAR(half, edge, 0.01f);
    EXPECT_NEAR(width, 0.8f * c.grid.scale, 0.01f);
    EXPECT_GE(c.rebases, 1);  // the light drifts past kShiftTexels: a shift was exercised
    if (!orthographic) {
      EXPECT_LT(c.grid.scale, 0.7f);
    }

    // The same edge re-sampled every slab (convolve_slab with one tap).
    std::vector<float> a(std::size_t(kW * kH)), b(a.size());
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) a[std::size_t(x + kW * y)] = float(x) + 0.5f < 21.0f ? 0.0f : 1.0f;
    const SlabKernel k = single_tap_kernel();
    for (int s = 1; s <= slabs; ++s) {
      convolve_slab(f, k, a.data(), b.data(), z0 + float(s) * f.slab_distance);
      a.swap(b);
    }
    const std::vector<float> resampled = read_row([&](vec2 p) { return read_buffer(a.data(), kW, kH, p); });
    const float resampled_width = crossing(resampled, 0.9f) - crossing(resampled, 0.1f);
    std::printf("  re-sampled every slab: edge at %.3f, 10-90 width %.3f px\n", crossing(resampled, 0.5f),
                resampled_width);
    EXPECT_NEAR(crossing(resampled, 0.5f), edge, 1.0f);  // the same maps; its clamped Catmull-Rom reads lag (docs/convolution.md)
    EXPECT_GT(resampled_width, 2.0f * width);
  }
}

// Below the scale the grid was sized for, it is re-sampled onto the pixel
// grid (scale 1) and goes on from there: the edge stays where the maps put
// it, and a handful of sharp re-samples keep it within a pixel or so.
TEST(CarriedLight, ReSamplesOntoThePixelGridWhenShrunkTooFar) {
  const SlabFrame f = perspective_frame();
  Carried c;
  const float z0 = 10.0f;  // 10 -> 40: the grid would shrink to a quarter
  const float edge = carry_edge(c, f, z0, 60, 19.0f, 0.5f);
  const std::vector<float> row = read_row(
      [&](vec2 p) { return read_buffer(c.texels[c.half].data(), c.grid.width, c.grid.height, c.grid.texel_of(p)); });
  const float half = crossing(row, 0.5f), width = crossing(row, 0.9f) - crossing(row, 0.1f);
  std::printf("edge at %.3f (maps: %.3f), 10-90 width %.3f px, scale %.3f\n", half, edge, width, c.grid.scale);
  EXPECT_NEAR(half, edge, 0.25f);
  EXPECT_GE(c.grid.scale, 0.5f);  // re-based: z quadrupled, the grid did not follow below half
  EXPECT_LT(width, 1.0f);
}

// The four pixels around a position, as a bilinear read takes them.
TEST(CarriedLight, MediumMaskChecksTheFourPixelsAroundAPosition) {
  constexpr int kFw = 6, kFh = 5;
  for (const ivec2& flagged : {ivec2(3, 2), ivec2(0, 0), ivec2(5, 4)}) {
    MediumMask mask;
    mask.resize(kFw, kFh);
    mask.flags()[flagged.x + kFw * flagged.y] = 1;
    mask.build();
    for (float y = -1.0f; y < float(kFh) + 1.0f; y += 0.25f) {
      for (float x = -1.0f; x < float(kFw) + 1.0f; x += 0.25f) {
        const float fx = std::floor(x - 0.5f), fy = std::floor(y - 0.5f);
        bool expected = false;  // brute force: the clamped 2 x 2 neighbourhood
        for (int j = 0; j < 2; ++j)
          for (int i = 0; i < 2; ++i)
            expected = expected || (glm::clamp(int(fx) + i, 0, kFw - 1) == flagged.x &&
                                    glm::clamp(int(fy) + j, 0, kFh - 1) == flagged.y);
        EXPECT_EQ(mask.touches(vec2(x, y)), expected) << x << ", " << y;
      }
    }
  }
}

// A slab loop in miniature (orthographic, a tilted light): an opaque edge in
// the first slab, then 80 slabs of empty space. The pixel grid's light is
// re-sampled every slab (convolve_slab with one tap) and attenuated by its
// own column; with the carried grid beside it, the light that crossed empty
// space comes from the grid instead. The edge arrives where the slab maps put
// it, about a pixel wide (two bilinear reads) instead of several; with
// medium in every slab nothing is taken from the grid.
struct MiniLoop {
  float edge_half = 0.0f, width = 0.0f, analytic = 0.0f;
  float drift = 0.0f;  // w.x, the light's sideways step per slab (pixels; the same every slab here)
  std::vector<float> light;
  std::uint64_t free_pixels = 0;
};

MiniLoop mini_loop(bool carry, float haze, int thick = 1, float block = 50.0f) {
  const SlabFrame f = perspective_frame(true);
  const std::size_t pixels = std::size_t(kW * kH);
  std::vector<float> a(pixels, 1.0f), b(pixels), depth(pixels, 0.0f);
  const SlabKernel k = single_tap_kernel();
  const vec2 tap = kTap;
  CarriedLights carried;
  carried.start(kW, kH, 1, 1.0f, 13, {char(carry)});  // 13: a pixel at 0.08 px per slab
  MiniLoop out;
  out.analytic = 21.0f;
  const int slabs = 80;
  for (int s = 0; s <= slabs; ++s) {
    const float z = 30.0f + float(s) * f.slab_distance;
    if (s > 0) {
      const SlabMapping m = slab_mapping(f, z);
      const vec2 w = m.pixels_per_unit * vec2(-tap.x, tap.y);
      if (carry) {
        MediumMask medium;
        medium.resize(kW, kH);
        for (std::size_t i = 0; i < pixels; ++i) {
          medium.flags()[i] = depth[i] > 0.0f;
          medium.extinction()[i] = depth[i];
        }
        medium.build();
        carried.advance(0, 1.0f, medium, m, w);
        out.free_pixels += carried.propagate(0, f, k, a.data(), b.data(), medium, m, w);
      } else {
        convolve_slab(f, k, a.data(), b.data(), z);
      }
      a.swap(b);
      out.analytic -= w.x;  // orthographic: s = 1
      out.drift = w.x;
    }
    // The pixels' pass: this slab's optical depth, and the light leaving it.
    for (int y = 0; y < kH; ++y) {
      for (int x = 0; x < kW; ++x) {
        const std::size_t i = std::size_t(x + kW * y);
        depth[i] = (s < thick && float(x) + 0.5f < 21.0f) ? block : haze;
        a[i] *= std::exp(-depth[i]);
      }
    }
  }
  out.light = a;
  const std::vector<float> row = read_row([&](vec2 p) { return read_buffer(a.data(), kW, kH, p); });
  const float lit = std::exp(-haze * float(slabs));
  out.edge_half = crossing(row, 0.5f * lit);
  out.width = crossing(row, 0.9f * lit) - crossing(row, 0.1f * lit);
  return out;
}

TEST(CarriedLight, LightCrossesEmptySpaceOnTheGridAndMediaOnThePixels) {
  const MiniLoop carried = mini_loop(true, 0.0f), resampled = mini_loop(false, 0.0f);
  std::printf("edge after 80 empty slabs: carried at %.3f, width %.3f px; re-sampled at %.3f, width %.3f px; "
              "analytic %.3f\n",
              carried.edge_half, carried.width, resampled.edge_half, resampled.width, carried.analytic);
  EXPECT_NEAR(carried.edge_half, carried.analytic, 0.15f);
  EXPECT_LT(carried.width, 1.8f);  // 1.58: the step, its read onto the grid and back, each bilinear
  EXPECT_GT(resampled.width, 2.0f * carried.width);
  EXPECT_GT(carried.free_pixels, 0u);

  // Haze in every slab: every pixel's light crossed a medium, so the grid
  // gives nothing and the light is the re-sampled one, bit for bit.
  const MiniLoop hazy = mini_loop(true, 1e-3f), hazy_resampled = mini_loop(false, 1e-3f);
  EXPECT_EQ(hazy.free_pixels, 0u);
  EXPECT_EQ(hazy.light, hazy_resampled.light);
}

// Light that leaves a thick occluder (40 slabs of it, the light crossing its
// side) keeps its own value on the grid, attenuated by each slab's
// transmittance where it crossed, instead of taking the pixel grid's light,
// which is re-sampled every slab inside: an opaque block's shadow edge stays
// where the rays put it and as narrow as a thin plate's (1.58 px at 27.33
// against 27.40; taking the pixel grid's light: 2.31 px at 26.93), and a hazy
// block's shadow follows exact rays along the row (rms 0.0175; the pixel
// grid's light: 0.0357).
TEST(CarriedLight, LightLeavingAThickOccluderIsNotBlurredInIt) {
  const MiniLoop opaque = mini_loop(true, 0.0f, 40, 50.0f);
  std::printf("opaque block, 40 slabs: edge at %.3f, width %.3f px; analytic %.3f\n", opaque.edge_half, opaque.width,
              opaque.analytic);
  EXPECT_NEAR(opaque.edge_half, opaque.analytic, 0.15f);
  EXPECT_LT(opaque.width, 1.8f);

  const float block = 0.05f;
  const int thick = 40;
  const MiniLoop hazy = mini_loop(true, 0.0f, thick, block);
  // Pixel centre X of the row was at X + (80 - j) w.x on slab j, in the block
  // where that is left of x = 21.
  double sum = 0.0;
  for (int x = 0; x < kW; ++x) {
    const float X = float(x) + 0.5f;
    int inside = 0;
    for (int j = 0; j < thick; ++j) inside += X + float(80 - j) * hazy.drift < 21.0f;
    const float exact = std::exp(-block * float(inside));
    const float got = hazy.light[std::size_t(x + kW * (kH / 2))];
    sum += double(got - exact) * double(got - exact);
  }
  const double rms = std::sqrt(sum / kW);
  std::printf("hazy block, 40 slabs: rms against exact rays along the row %.4f\n", rms);
  EXPECT_LT(rms, 0.026);
}

}  // namespace
}  // namespace carried_light_test
}  // namespace penumbra

#pragma once
// Step (2) of Patel et al. 2013, section 4.2, for one pixel and slab: walk the
// pixel's layered depth image fragments that lie in front of the slab's back
// face, flipping each mesh's inside/outside parity (the paper's single parity
// bit, kept per mesh so overlapping meshes work), and measure how much of the
// slab's depth interval [z0, z1] lies inside any mesh. The mesh medium is
// sampled once in the span of that inside part: at its middle, or at the
// pixel's jitter offset along it (the paper samples at the intersection point
// or a jittered point in the slab). The covered length weighs the sample, so
// a homogeneous interior integrates exactly wherever the sample sits, as the
// volume's segment rule does (DESIGN-NOTES "Sampling").
#include "penumbra/techniques/convolution/layered_depth_image.h"

#include <cstdint>

namespace penumbra {

struct PixelLayers {
  std::uint32_t next = 0;    // the next fragment to cross
  std::uint32_t end = 0;     // one past the pixel's last fragment
  std::uint32_t inside = 0;  // bit m: inside mesh m
};

struct SlabCoverage {
  float length = 0.0f;  // depth inside any mesh within [z0, z1]
  float middle = 0.0f;  // depth of the middle of the covered part
  float first = 0.0f, last = 0.0f;  // depth span of the covered part (gaps included)
  std::uint32_t objects = 0;  // meshes inside at any point of the slab
  int entry = -1;             // the first fragment entering a mesh in this slab (surface highlight), or -1
};

// The starting parity of each mesh: a mesh whose first fragment on this pixel
// leaves it contains the start of the ray (a camera inside a mesh).
PENUMBRA_HD inline PixelLayers start_layers(const LdiView& ldi, int x, int y) {
  PixelLayers p;
  const std::size_t i = std::size_t(x) + std::size_t(ldi.width) * std::size_t(y);
  p.next = ldi.offsets[i];
  p.end = ldi.offsets[i + 1];
  std::uint32_t seen = 0;
  for (std::uint32_t f = p.next; f < p.end; ++f) {
    const LdiFragment& frag = ldi.fragments[f];
    const std::uint32_t bit = 1u << frag.object;
    if (!(seen & bit) && !frag.entering) p.inside |= bit;
    seen |= bit;
  }
  return p;
}

PENUMBRA_HD inline SlabCoverage cross_slab(const LdiView& ldi, PixelLayers& p, float z0, float z1) {
  SlabCoverage c;
  float at = z0, first = z1, last = z0;
  c.objects = p.inside;
  while (p.next < p.end && ldi.fragments[p.next].depth < z1) {
    const LdiFragment& f = ldi.fragments[p.next];
    const float d = glm::clamp(f.depth, z0, z1);
    if (p.inside != 0u && d > at) {
      c.length += d - at;
      first = glm::min(first, at);
      last = d;
    }
    at = glm::max(at, d);
    p.inside ^= 1u << f.object;
    c.objects |= p.inside;
    if (f.entering && c.entry < 0) c.entry = int(p.next);
    ++p.next;
  }
  if (p.inside != 0u && z1 > at) {
    c.length += z1 - at;
    first = glm::min(first, at);
    last = z1;
  }
  c.middle = c.length > 0.0f ? 0.5f * (first + last) : 0.5f * (z0 + z1);
  c.first = c.length > 0.0f ? first : c.middle;
  c.last = c.length > 0.0f ? last : c.middle;
  return c;
}

}  // namespace penumbra
